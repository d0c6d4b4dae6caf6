// A record's screen footprint (docs/ALGORITHM.md section 3): the conservative pixel rectangle of the sphere a record can
// reach, shared by the placement and splat kernels. Device-only: the host's octree finds neighbours in world space.
#ifndef RCSPLAT_FOOTPRINT_H
#define RCSPLAT_FOOTPRINT_H
#include "cache_math.h"
#include "sampling.h"

typedef struct {
  int x0, y0, x1, y1;  // inclusive; empty when x0 > x1 or y0 > y1
} PixelRect;

// A conservative screen rectangle of the sphere (center, radius): the projection of its camera-aligned bounding cube,
// plus a pixel of margin for rounding. The whole screen when the cube reaches behind a perspective camera's eye.
inline PixelRect sphere_footprint(__global const CameraParams* cam, float3 center, float radius) {
  PixelRect rect = {0, 0, cam->width - 1, cam->height - 1};
  float3 rel = center - vload3(0, cam->eye);
  float cx = dot(rel, vload3(0, cam->right)), cy = dot(rel, vload3(0, cam->up));
  float x_lo = cx - radius, x_hi = cx + radius, y_lo = cy - radius, y_hi = cy + radius;
  float sx_min, sx_max, sy_min, sy_max;  // the cube's extent in screen coordinates, -1 .. 1 across the image
  if (cam->orthographic) {  // parallel projection: no division by depth
    float half_width = cam->half_height * cam->aspect;
    sx_min = x_lo / half_width;
    sx_max = x_hi / half_width;
    sy_min = y_lo / cam->half_height;
    sy_max = y_hi / cam->half_height;
  } else {
    float cz = dot(rel, vload3(0, cam->forward));
    float z_near = cz - radius, z_far = cz + radius;
    if (!(z_near > 1e-6f * z_far) || !isfinite(z_far)) return rect;
    float tx = cam->tan_half_fov_y * cam->aspect, ty = cam->tan_half_fov_y;
    // x / z over the cube is extreme at one of its z faces, chosen by the sign of x.
    sx_min = x_lo / (x_lo < 0.0f ? z_near : z_far) / tx;
    sx_max = x_hi / (x_hi > 0.0f ? z_near : z_far) / tx;
    sy_min = y_lo / (y_lo < 0.0f ? z_near : z_far) / ty;
    sy_max = y_hi / (y_hi > 0.0f ? z_near : z_far) / ty;
  }
  if (!isfinite(sx_min + sx_max + sy_min + sy_max)) return rect;
  // Pixel x has its centre at s = 2 (x + 0.5) / width - 1; pixel y at s = 1 - 2 (y + 0.5) / height.
  float px_min = (sx_min + 1.0f) * 0.5f * (float)cam->width - 0.5f;
  float px_max = (sx_max + 1.0f) * 0.5f * (float)cam->width - 0.5f;
  float py_min = (1.0f - sy_max) * 0.5f * (float)cam->height - 0.5f;
  float py_max = (1.0f - sy_min) * 0.5f * (float)cam->height - 0.5f;
  // Clamped in float before converting: an off-screen sphere gives an empty rectangle, never an overflow.
  float w = (float)cam->width, h = (float)cam->height;
  rect.x0 = (int)clamp(floor(px_min) - 1.0f, 0.0f, w);
  rect.y0 = (int)clamp(floor(py_min) - 1.0f, 0.0f, h);
  rect.x1 = (int)clamp(ceil(px_max) + 1.0f, -1.0f, w - 1.0f);
  rect.y1 = (int)clamp(ceil(py_max) + 1.0f, -1.0f, h - 1.0f);
  return rect;
}

#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
// Adds w * value (at the fixed-point unit to_fixed, FIXED_POINT_ONE / scale) and w to a pixel's four 64-bit sums: the
// same totals whatever order the splat's records land in.
inline void add_weighted_fixed_point(__global long* sum, float w, float3 value, float to_fixed) {
  float3 weighted = (w * to_fixed) * value;
  atom_add(sum + 0, convert_long(weighted.x));
  atom_add(sum + 1, convert_long(weighted.y));
  atom_add(sum + 2, convert_long(weighted.z));
  atom_add(sum + 3, convert_long(w * FIXED_POINT_ONE));
}

// A pixel's sums back to (sum(w value) / sum(w), sum(w)) at the unit scale: zero value where no record reached.
inline float4 normalized_fixed_point(long4 s, float scale) {
  float3 value = (float3)(0.0f);
  if (s.w > 0) value = convert_float3(s.xyz) / (float)s.w * scale;
  return (float4)(finite_or_zero(value), (float)s.w / FIXED_POINT_ONE);
}

#endif
