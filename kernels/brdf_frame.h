// The BRDF's local frame at a shading point and what a pixel's shading needs from it: the view direction from the
// camera, the BRDF inputs a G-buffer sample holds, and the specular lobe's directional albedo. No tracing here, so
// the splat's resolve kernel can include it without the traversal's floating-point pragmas.
#ifndef RCSPLAT_BRDF_FRAME_H
#define RCSPLAT_BRDF_FRAME_H
#include "brdf.h"
#include "sampling.h"
#include "shared_types.h"

// An orthonormal frame with the shading normal as +z, the BRDF's local frame.
typedef struct {
  float3 t, b, n;
} ShadingFrame;

inline ShadingFrame shading_frame(float3 n) {
  ShadingFrame f;
  f.n = n;
  tangent_frame(n, &f.t, &f.b);
  return f;
}

inline float3 to_local(ShadingFrame f, float3 v) { return (float3)(dot(v, f.t), dot(v, f.b), dot(v, f.n)); }
inline float3 to_world(ShadingFrame f, float3 v) { return v.x * f.t + v.y * f.b + v.z * f.n; }

// The view direction in the local frame. An interpolated normal can tilt past the viewer (the geometric normal still
// faces it): the view is then taken just above the horizon rather than losing the pixel's reflection.
inline float3 view_local(ShadingFrame f, float3 wo_world) {
  float3 wo = to_local(f, wo_world);
  if (wo.z < 1e-4f) wo = normalize((float3)(wo.x, wo.y, 1e-4f));
  return wo;
}

// The unit direction from p toward the camera that sees it.
inline float3 camera_view_direction(__global const CameraParams* cam, float3 p) {
  if (cam->orthographic) return -vload3(0, cam->forward);
  return normalize(vload3(0, cam->eye) - p);
}

// The BRDF at a G-buffer sample.
inline BrdfInputs gbuffer_brdf(GBufferSample g) {
  return brdf_inputs(vload3(0, g.albedo), g.metallic, g.roughness, g.specular);
}

// The specular lobe's directional albedo, through a table shared by all materials. The lobe's Fresnel colour is
// c0 + c1 (1 - v.h)^5 (specular_fresnel_terms), so its albedo toward wo is c0 T0 + c1 T1 with
// T0 = integral of G2 / G1 and T1 = integral of (1 - v.h)^5 G2 / G1 over the visible normals: two numbers per view angle
// and roughness, tabulated once (kernels/compose.cl specular_albedo_table) and read bilinearly.

// Entry (T0, T1) for cos(theta_o) and roughness, by a 64 x 64 midpoint rule over the visible normals (the integrand
// jumps where reflections fall below the horizon: 16 x 16 left 2% errors at roughness 1).
inline float2 specular_albedo_terms(float cos_o, float roughness) {
  cos_o = fmax(cos_o, 1e-3f);  // the grazing node: G1 vanishes at 0
  BrdfInputs in = brdf_inputs((float3)(1.0f), 1.0f, roughness, 1.0f);
  float3 wo = (float3)(sqrt(fmax(1.0f - cos_o * cos_o, 0.0f)), 0.0f, cos_o);
  float a2 = in.alpha * in.alpha;
  float2 sum = (float2)(0.0f);
  const int side = 64;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      float3 h = ggx_sample_visible_normal(wo, in.alpha, ((float)j + 0.5f) / side, ((float)i + 0.5f) / side);
      float3 wi = 2.0f * dot(wo, h) * h - wo;
      if (wi.z <= 0.0f) continue;
      float g2_over_g1 = ggx_g2_over_g1(wi.z, wo.z, a2);
      float fw = schlick_weight(fmax(dot(wo, h), 0.0f));
      sum += (float2)(g2_over_g1, fw * g2_over_g1);
    }
  }
  return sum * (1.0f / (float)(side * side));
}

// The table's (T0, T1) for a view at cos_o to the normal and the lobe's roughness, read bilinearly.
inline float2 specular_albedo_split(__global const float2* table, BrdfInputs in, float cos_o) {
  const int n = SPECULAR_ALBEDO_TABLE_SIZE;
  float x = clamp(cos_o, 0.0f, 1.0f) * (float)(n - 1), y = clamp(sqrt(in.alpha), 0.0f, 1.0f) * (float)(n - 1);
  int x0 = min((int)x, n - 2), y0 = min((int)y, n - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  float2 bottom = mix(table[y0 * n + x0], table[y0 * n + x0 + 1], fx);
  float2 top = mix(table[(y0 + 1) * n + x0], table[(y0 + 1) * n + x0 + 1], fx);
  return mix(bottom, top, fy);
}

// The specular lobe's directional albedo toward wo (local frame), from the table.
inline float3 specular_albedo(__global const float2* table, BrdfInputs in, float3 wo) {
  float2 t = specular_albedo_split(table, in, wo.z);
  float3 c0, c1;
  specular_fresnel_terms(in, &c0, &c1);
  return c0 * t.x + c1 * t.y;
}

#endif
