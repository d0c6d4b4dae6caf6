// The occlusion Hessian of a record's irradiance (Schwarzhaupt, Jensen, Jarosz, "Practical Hessian-based error
// control for irradiance caching", SIGGRAPH Asia 2012): the record's hemisphere hits, joined into a triangle mesh, are
// polygons of constant radiance whose form factor's second derivatives have a closed form per edge. The radius then
// follows the irradiance's curvature rather than Ward's split-sphere guess: large on open, evenly lit floors, small
// near contact shadows and occluders.
//
// Lambert: the form factor of a polygon seen from x (receiver normal n) is F = 1/(2 pi) sum_edges theta_e n.c_e/|c_e|
// with, for an edge from a to b, r_a = a - x, r_b = b - x, e = b - a, c = r_a x r_b and theta_e the angle between r_a
// and r_b. With r(t) = r_a + t e: theta/|c| = I1 = integral_0^1 dt/|r|^2, so F = 1/(2 pi) sum I1 n.c. Moving x moves
// r(t) and c (grad n.c = n x e, grad 1/|r|^2 = 2 r/|r|^4), hence per edge
//   grad F = 1/(2 pi) (I1 n x e + 2 n.c integral r/|r|^4)
//   hess F = 1/pi (sym(n x e, integral r/|r|^4) + n.c (4 integral r r^T/|r|^6 - I2 Id)),   sym(u, v) = u v^T + v u^T,
// with I2 = integral 1/|r|^4 and the moment integrals from the recurrences for integral dt / q(t)^k of the quadratic
// q = |r|^2 (whose discriminant is 4 |c|^2). Only the Hessian's tangent-plane block matters: a record moves along its
// surface.
#ifndef RCSPLAT_RECORD_HESSIAN_H
#define RCSPLAT_RECORD_HESSIAN_H

// The tangent-plane block of a symmetric 3 x 3 matrix in the frame (t, b): (tt, tb, bb).
typedef float3 TangentBlock;

// One edge's term of its polygon's form-factor Hessian, from vertex a to vertex b as seen from the origin (r_a, r_b
// relative to the receiver), projected on the receiver's (t, b). A polygon's Hessian is the sum over its edges in
// one winding; an edge shared by two polygons of radiance L1 and L2 (wound oppositely) contributes (L1 - L2) times it.
// Degenerate edges (coincident vertices, or vertices in line with the receiver) contribute nothing.
inline TangentBlock edge_form_factor_hessian(float3 r_a, float3 r_b, float3 n, float3 t, float3 b) {
  // The recurrences take moments about r_a; from the far end of an edge across a depth step (a hit 0.01 away beside
  // one 10 away) their sums cancel in float (measured: errors up to 8x the value). From the near end they do not
  // (below 3e-3 relative), and the reversed edge is the negated term.
  float sign = 1.0f;
  if (dot(r_a, r_a) > dot(r_b, r_b)) {
    float3 swap = r_a;
    r_a = r_b;
    r_b = swap;
    sign = -1.0f;
  }
  float3 e = r_b - r_a, c = cross(r_a, r_b);
  float cc = dot(c, c), ee = dot(e, e), aa = dot(r_a, r_a), bb = dot(r_b, r_b);
  // Relative tests, so that scale does not matter: |c|^2 against |r_a|^2 |r_b|^2 is sin^2 of the angle.
  if (!(cc > 1e-12f * aa * bb) || !(ee > 1e-12f * (aa + bb))) return (TangentBlock)(0.0f);
  float ea = dot(e, r_a), eb = dot(e, r_b);
  float inv_a = 1.0f / aa, inv_b = 1.0f / bb, inv_cc = 1.0f / cc, inv_ee = 1.0f / ee;
  float i1 = atan2(sqrt(cc), dot(r_a, r_b)) * rsqrt(cc);
  float i2 = 0.5f * inv_cc * (eb * inv_b - ea * inv_a + ee * i1);
  float j2 = inv_ee * (0.5f * (inv_a - inv_b) - ea * i2);
  float i3 = 0.25f * inv_cc * (eb * inv_b * inv_b - ea * inv_a * inv_a + 3.0f * ee * i2);
  float j3 = inv_ee * (0.25f * (inv_a * inv_a - inv_b * inv_b) - ea * i3);
  float k3 = inv_ee * (i2 - aa * i3 - 2.0f * ea * j3);
  float3 rho = i2 * r_a + j2 * e;  // integral r / |r|^4
  float3 m = cross(n, e);
  float nc = dot(n, c);
  float mt = dot(m, t), mb = dot(m, b), pt = dot(rho, t), pb = dot(rho, b);
  float at = dot(r_a, t), ab = dot(r_a, b), et = dot(e, t), eb_ = dot(e, b);
  // integral r r^T / |r|^6 = i3 r_a r_a^T + j3 (r_a e^T + e r_a^T) + k3 e e^T, projected.
  float qtt = i3 * at * at + 2.0f * j3 * at * et + k3 * et * et;
  float qtb = i3 * at * ab + j3 * (at * eb_ + et * ab) + k3 * et * eb_;
  float qbb = i3 * ab * ab + 2.0f * j3 * ab * eb_ + k3 * eb_ * eb_;
  return (sign * RC_INV_PI) * (TangentBlock)(2.0f * mt * pt + nc * (4.0f * qtt - i2), mt * pb + pt * mb + nc * 4.0f * qtb,
                                    2.0f * mb * pb + nc * (4.0f * qbb - i2));
}

// The largest eigenvalue magnitude of a symmetric 2 x 2 block: how fast the value's slope changes along the steepest
// direction.
inline float largest_curvature(TangentBlock h) {
  float mean = 0.5f * (h.x + h.z), half_diff = 0.5f * (h.x - h.z);
  return fabs(mean) + sqrt(half_diff * half_diff + h.y * h.y);
}

#endif
