// The scene's triangles cut into the photon map's surface patches on the device (host/passes/surface_patch_pass.h):
// the host's surface_patches (host/cache/photon_map.cpp PatchedTriangle) bit for bit, by the same double-precision
// operations in the same order, so only built for a device with doubles (cl_khr_fp64); on another the host cuts them.
// Each triangle's patch count, scanned (kernels/scan.cl) into where its patches start, then each writes its own.
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "shared_types.h"

// A huge triangle gets patches larger than asked: still its exact area.
#define PATCH_MAX_CUTS 256.0

typedef struct {
  double3 a, e1, e2, n;
  int cuts;    // the n x n cut into sub-triangles; 0: a degenerate triangle, no patch
  float area;  // each sub-triangle's
} PatchedTriangle;

// As glm::cross and glm::length do it, term for term.
inline double3 cross_as_glm(double3 x, double3 y) {
  return (double3)(x.y * y.z - y.y * x.z, x.z * y.x - y.z * x.x, x.x * y.y - y.x * x.y);
}
inline double length_as_glm(double3 v) {
  const double3 squares = v * v;
  return sqrt(squares.x + squares.y + squares.z);
}

inline PatchedTriangle patched_triangle(__global const float* corners, uint t, float patch_area) {
  __global const float* c = corners + 9 * (size_t)t;
  PatchedTriangle p;
  p.a = (double3)(c[0], c[1], c[2]);
  p.e1 = (double3)(c[3], c[4], c[5]) - p.a;
  p.e2 = (double3)(c[6], c[7], c[8]) - p.a;
  p.n = (double3)(0.0);
  p.cuts = 0;
  p.area = 0.0f;
  const double3 normal = cross_as_glm(p.e1, p.e2);
  const double twice_area = length_as_glm(normal);
  if (!(twice_area > 0.0) || !isfinite(twice_area)) return p;
  p.n = normal / twice_area;
  const double cuts = ceil(sqrt(0.5 * twice_area / (double)patch_area));
  p.cuts = (int)(cuts < 1.0 ? 1.0 : (PATCH_MAX_CUTS < cuts ? PATCH_MAX_CUTS : cuts));
  p.area = (float)(0.5 * twice_area / (double)(p.cuts * p.cuts));
  return p;
}

// counts[t]: triangle t's patches (its cuts^2 sub-triangles, two sides each); *total: all of them, in 64 bits, so
// that the host can refuse a count the 32-bit scan would wrap.
__kernel void count_triangle_patches(__global const float* corners, uint triangle_count, float patch_area,
                                     __global uint* counts, __global ulong* total) {
  const uint t = get_global_id(0);
  if (t >= triangle_count) return;
  const PatchedTriangle p = patched_triangle(corners, t, patch_area);
  counts[t] = 2u * (uint)p.cuts * (uint)p.cuts;
  if (p.cuts) atom_add(total, (ulong)counts[t]);
}

// The patches of sub-triangle centroid (u, v) (in units of the edges over cuts): one a side.
inline void write_patch_pair(PatchedTriangle p, double u, double v, __global SurfacePatch* out) {
  const double3 x = p.a + (u / (double)p.cuts) * p.e1 + (v / (double)p.cuts) * p.e2;
  for (int s = 0; s < 2; ++s) {
    const double side = s == 0 ? 1.0 : -1.0;
    SurfacePatch patch;
    patch.position[0] = (float)x.x;
    patch.position[1] = (float)x.y;
    patch.position[2] = (float)x.z;
    patch.area = p.area;
    patch.normal[0] = (float)(side * p.n.x);
    patch.normal[1] = (float)(side * p.n.y);
    patch.normal[2] = (float)(side * p.n.z);
    patch.pad = 0.0f;
    out[s] = patch;
  }
}

// Triangle t's patches from firsts[t] on: the upward sub-triangles at (i + 1/3, j + 1/3), the downward ones between
// them at (i + 2/3, j + 2/3), row by row as the host writes them.
__kernel void write_triangle_patches(__global const float* corners, uint triangle_count, float patch_area,
                                     __global const uint* firsts, __global SurfacePatch* patches) {
  const uint t = get_global_id(0);
  if (t >= triangle_count) return;
  const PatchedTriangle p = patched_triangle(corners, t, patch_area);
  __global SurfacePatch* out = patches + firsts[t];
  for (int i = 0; i < p.cuts; ++i)
    for (int j = 0; i + j < p.cuts; ++j) {
      write_patch_pair(p, (double)i + 1.0 / 3.0, (double)j + 1.0 / 3.0, out);
      out += 2;
      if (i + j + 1 < p.cuts) {
        write_patch_pair(p, (double)i + 2.0 / 3.0, (double)j + 2.0 / 3.0, out);
        out += 2;
      }
    }
}
