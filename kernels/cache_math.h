// The irradiance cache's math (docs/ALGORITHM.md sections 3 and 4), one source compiled by the kernels and by the host:
// Ward's weight, the usability and in-front tests, gradient extrapolation, the neighbour clamp, the splat's
// fixed-point scale, and the constants they share. The splat, the placement kernels and the host's octree cache all
// decide with these functions, so the two cache methods place the same records.
// Not built on it, on purpose: tests/reference/host_records.cpp computes records in double precision, written
// independently, as the record kernel's test reference.
#ifndef RCSPLAT_CACHE_MATH_H
#define RCSPLAT_CACHE_MATH_H
#include "host_device.h"
#include "shared_types.h"

// Ward's weight is infinite at the record itself; the cap keeps fixed-point sums bounded (see FIXED_POINT_ONE).
#define MAX_RECORD_WEIGHT 1.0e3f
// The accuracy a: a record reaches points where its weight exceeds 1/a. A record's own pixel has the capped weight,
// so a must exceed 1/MAX_RECORD_WEIGHT for records to cover themselves; the lower limit keeps a decade of margin,
// so usable weights (above 1/a, at most the cap) span at least a decade. Above the upper limit the threshold admits
// points a hundred radii away, where Ward's weight no longer describes the error.
#define MIN_ACCURACY (10.0f / MAX_RECORD_WEIGHT)
#define MAX_ACCURACY 100.0f
// The in-front test tolerates points this far (in radii) in front of the record's tangent plane (Ward's 0.05,
// scale-free).
#define IN_FRONT_TOLERANCE 0.05f
// Placement marks which TILE x TILE pixel tiles hold a record of the newest batch (older records only look there).
#define PLACEMENT_TILE_SIZE 16
// Fixed-point unit of the splat's sums, 2^48: w <= MAX_RECORD_WEIGHT = 1e3 and w * E / irradiance_scale <= w, so one
// contribution is below 2^58. Only a record's own pixel can bring w above (max spacing) / a (about 70 at the
// defaults: other pixels are at least a pixel footprint away), so a sum would need hundreds of records on one pixel
// to reach 2^63. Resolution: an irradiance 1e-9 of the frame's largest still has about 2^18 units.
#define FIXED_POINT_ONE 281474976710656.0f

// 1 / (|P - Pk| / R + sqrt(1 - n.nk)), with sqrt(1 - n.nk) computed as |n - nk| / sqrt(2), which keeps its precision
// for nearly equal normals (docs/ALGORITHM.md section 3).
inline float ward_weight(rc_float3 p, rc_float3 n, rc_float3 pk, rc_float3 nk, float radius) {
  float denom = rc_length(p - pk) / radius + rc_length(n - nk) * 0.70710678f;
  return denom * MAX_RECORD_WEIGHT > 1.0f ? 1.0f / denom : MAX_RECORD_WEIGHT;
}

// Ward's "not in front" test: P may use the record unless it lies in front of the record's tangent plane (seen
// along the mean normal) by more than the tolerance.
inline bool not_in_front_of_record(rc_float3 p, rc_float3 n, rc_float3 pk, rc_float3 nk, float radius) {
  return rc_dot(p - pk, n + nk) * 0.5f >= -IN_FRONT_TOLERANCE * radius;
}

// Record k may be used at P (normal n): its weight w there exceeds 1/a, it faces the same way, and P is not in front.
inline bool record_usable(float w, float accuracy, rc_float3 p, rc_float3 n, rc_float3 pk, rc_float3 nk, float radius) {
  return w * accuracy > 1.0f && rc_dot(n, nk) > 0.0f && not_in_front_of_record(p, n, pk, nk, radius);
}

// The 45-degree azimuth sector (0 .. 7, counter-clockwise from t) of the tangent-plane offset (x, y), by comparisons
// only, so that the host and the device agree to the bit.
inline int horizon_sector(float x, float y) {
  if (y >= 0.0f) return x > 0.0f ? (y < x ? 0 : 1) : (y > -x ? 2 : 3);
  return x < 0.0f ? (-y < -x ? 4 : 5) : (-y > x ? 6 : 7);
}

// Rays below this elevation (sin^2 theta at least this) find the occluders a record stands beside.
#define HORIZON_MIN_SIN2_THETA 0.75f

// Thin-wall leaks: a record may not reach P if P lies, along the record's tangent plane, beyond the occluder its low
// rays found in P's direction (the far side of a wall it stands beside, thinner than a pixel). (t, b): the record's
// tangent_frame, computed once per record by the caller. The offset's normal component does not change x, y.
inline bool within_record_horizon(RC_GLOBAL const CacheRecord* rec, rc_float3 t, rc_float3 b, rc_float3 p) {
  rc_float3 d = p - rc_load3(0, rec->position);
  float x = rc_dot(d, t), y = rc_dot(d, b), h = rec->horizon[horizon_sector(x, y)];
  return x * x + y * y <= h * h;
}

// record_usable and within_record_horizon together: what the splat, placement and the octree ask of each record.
inline bool record_reaches(RC_GLOBAL const CacheRecord* rec, rc_float3 t, rc_float3 b, float w, float accuracy,
                           rc_float3 p, rc_float3 n, rc_float3 pk, rc_float3 nk, float radius) {
  return record_usable(w, accuracy, p, n, pk, nk, radius) && within_record_horizon(rec, t, b, p);
}

// A pixel no record reaches (with sub-pixels, placement stops one output pixel apart, so slivers along edges stay
// uncovered) takes a record sitting within `window` pixels of (x, y) (record_at_pixel: placement's map, -1 where none
// sits): the best Ward weight among those that face it, are not behind it and whose horizon does not hide it, else the
// best-weighted that faces it. Returns the record, -1 where none faces the pixel; *weight: its weight there. The splat,
// the radiance splat and the octree fill with this one rule.
inline int record_for_uncovered_pixel(RC_GLOBAL const CacheRecord* records, RC_GLOBAL const int* record_at_pixel,
                                      int width, int height, int x, int y, int window, rc_float3 p, rc_float3 n,
                                      float* weight) {
  float best = 0.0f, best_facing = 0.0f;
  int chosen = -1, facing = -1;
  for (int yy = y - window < 0 ? 0 : y - window; yy <= y + window && yy < height; ++yy) {
    for (int xx = x - window < 0 ? 0 : x - window; xx <= x + window && xx < width; ++xx) {
      int k = record_at_pixel[yy * width + xx];
      if (k < 0) continue;
      RC_GLOBAL const CacheRecord* rec = records + k;
      rc_float3 pk = rc_load3(0, rec->position), nk = rc_load3(0, rec->normal);
      if (rc_dot(n, nk) <= 0.0f) continue;
      float w = ward_weight(p, n, pk, nk, rec->radius);
      if (w > best_facing) {
        best_facing = w;
        facing = k;
      }
      rc_float3 tk, bk;
      tangent_frame(nk, &tk, &bk);
      if (w > best && not_in_front_of_record(p, n, pk, nk, rec->radius) && within_record_horizon(rec, tk, bk, p)) {
        best = w;
        chosen = k;
      }
    }
  }
  if (chosen < 0) {
    chosen = facing;
    best = best_facing;
  }
  *weight = best;
  return chosen;
}

// E_k(P) = max(0, E + (nk x n) . grad_r + (P - Pk) . grad_t), per channel.
inline rc_float3 extrapolated_irradiance(RC_GLOBAL const CacheRecord* rec, rc_float3 p, rc_float3 n) {
  rc_float3 dp = p - rc_load3(0, rec->position);
  rc_float3 dn = rc_cross(rc_load3(0, rec->normal), n);
  rc_float3 e = rc_load3(0, rec->irradiance);
  e += dp.x * rc_load3(0, rec->grad_translation) + dp.y * rc_load3(1, rec->grad_translation) +
       dp.z * rc_load3(2, rec->grad_translation);
  e += dn.x * rc_load3(0, rec->grad_rotation) + dn.y * rc_load3(1, rec->grad_rotation) +
       dn.z * rc_load3(2, rec->grad_rotation);
  return rc_max_zero(e);
}

// Neighbour clamping (Křivánek et al. 2006): record j bounds the radius of record i by R_j + |P_i - P_j|.
inline float neighbour_radius_bound(rc_float3 pi, rc_float3 pj, float radius_j) { return radius_j + rc_distance(pi, pj); }

// The clamped radius R_i, given the smallest neighbour_radius_bound over its neighbours (or R_i); the
// screen-space minimum (min_radius_pixels footprints) still holds, since a neighbour seen at another depth may have a
// smaller one.
inline float neighbour_clamped_radius(float radius, float smallest_neighbour_bound, float min_radius_pixels,
                                      float pixel_size) {
  return rc_fmax(rc_fmin(radius, smallest_neighbour_bound), rc_fmin(radius, min_radius_pixels * pixel_size));
}

// The fixed-point unit of w * E for a frame whose largest record irradiance component is `largest`: no
// extrapolated value exceeds (3 + a) times it once the gradients are bounded, so sums at this scale cannot overflow.
// Which screen-space clamp a record's reach sits at, for the summary: -1 the lower, 1 the upper, 0 neither (its reach
// in pixels within 0.01% of min_reach_pixels or max_reach_pixels). The host's count (host/render/placement.cpp) and
// the device's (kernels/layers.cl count_clamped_reaches) both ask this.
inline int reach_clamp_side(float accuracy, float radius, float pixel_size, float min_reach_pixels,
                            float max_reach_pixels) {
  const float reach_pixels = accuracy * radius / pixel_size;
  if (reach_pixels <= min_reach_pixels * 1.0001f) return -1;
  return reach_pixels >= max_reach_pixels * 0.9999f ? 1 : 0;
}

inline float fixed_point_irradiance_scale(float largest, float accuracy) {
  if (!(largest > 0.0f)) return 1.0f;  // no records, or nothing but darkness and NaN
  return rc_fmin(largest * (3.0f + accuracy), FLT_MAX);
}

// World size of one pixel at the point p (at its distance along the view axis; the same everywhere when orthographic).
inline float pixel_world_size(RC_GLOBAL const CameraParams* cam, rc_float3 p) {
  if (cam->orthographic) return 2.0f * cam->half_height / (float)cam->height;
  float z = rc_dot(p - rc_load3(0, cam->eye), rc_load3(0, cam->forward));
  return 2.0f * rc_fabs(z) * cam->tan_half_fov_y / (float)cam->height;
}

#endif
