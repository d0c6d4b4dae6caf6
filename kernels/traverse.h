// Eight-wide BVH traversal with a watertight triangle test (Woop, Benthin, Wald 2013), one ray per work-item.
// The node and block buffers are read as float8 rows (see Bvh8Node and TriangleBlock8 in shared_types.h):
// a node is 7 rows (six bound rows, then the child references), a block 10 rows (nine vertex rows, then prim ids).
#ifndef RCSPLAT_TRAVERSE_H
#define RCSPLAT_TRAVERSE_H
#include "shared_types.h"

// The watertight test needs its edge functions evaluated exactly as written: a fused multiply-add would round a*b - c*d
// differently from its mirror image on the neighbouring triangle (cracks), and would make the empty lanes' zero
// determinant non-zero. Every program is built without contraction (GpuContext's kProgramPrologue).
#include "counter_random.h"
#include "surface.h"

// The traversal's view of the scene: the BVH, and with alpha-masked materials (HAS_ALPHA_MASK) or glass
// (HAS_TRANSMISSION, kernels/glass.h) what a hit needs to know whether it landed in a hole or on glass. Every function
// that traces takes BVH_ARGS and passes BVH on.
#if HAS_ALPHA_MASK || HAS_TRANSMISSION
#define BVH_ARGS                                                                                                     \
  __global const float8 *nodes, __global const float8 *blocks, __global const TriangleShading *triangles,           \
      __global const Material *materials, __global const TextureInfo *textures, __global const uint *texels
#define BVH nodes, blocks, triangles, materials, textures, texels
#else
#define BVH_ARGS __global const float8 *nodes, __global const float8 *blocks
#define BVH nodes, blocks
#endif

#define NODE_ROWS 7
#define BLOCK_ROWS 10
#ifndef BVH_STACK_SIZE
#define BVH_STACK_SIZE 64
#endif

// Per-ray constants: the box test's scaled origin and inverse direction, the triangle test's axis permutation and shear.
typedef struct {
  float3 org;
  float3 dir;
  float3 inv_dir;
  float3 org_inv;  // org * inv_dir, so that a slab distance is one fma
  int near_x, near_y, near_z;  // row of the near plane per axis, chosen by the direction's sign
  int kx, ky, kz;
  float shear_x, shear_y, shear_z;
  float org_kx, org_ky, org_kz;
} RayPrecomp;

inline float safe_inverse(float d) {
  // A finite stand-in for 1/0 keeps (plane - origin) * inverse free of NaN.
  const float tiny = 1e-30f;
  return fabs(d) > tiny ? 1.0f / d : (d < 0.0f ? -1e30f : 1e30f);
}

inline RayPrecomp ray_precompute(float3 org, float3 dir) {
  RayPrecomp r;
  r.org = org;
  r.dir = dir;
  r.inv_dir = (float3)(safe_inverse(dir.x), safe_inverse(dir.y), safe_inverse(dir.z));
  r.org_inv = org * r.inv_dir;
  r.near_x = dir.x < 0.0f ? 1 : 0;
  r.near_y = dir.y < 0.0f ? 3 : 2;
  r.near_z = dir.z < 0.0f ? 5 : 4;
  float3 a = fabs(dir);
  int kz = (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  float dir_c[3] = {dir.x, dir.y, dir.z};
  float org_c[3] = {org.x, org.y, org.z};
  if (dir_c[kz] < 0.0f) {  // keep the winding so that the determinant's sign means the same for every ray
    int t = kx;
    kx = ky;
    ky = t;
  }
  r.kx = kx;
  r.ky = ky;
  r.kz = kz;
  r.shear_x = dir_c[kx] / dir_c[kz];
  r.shear_y = dir_c[ky] / dir_c[kz];
  r.shear_z = 1.0f / dir_c[kz];
  r.org_kx = org_c[kx];
  r.org_ky = org_c[ky];
  r.org_kz = org_c[kz];
  return r;
}

// Bit i set where lane i of a comparison is true. On an x86 device with AVX (PoCL's CPU devices), one movmskps of the
// lanes' sign bits, which LLVM turns into a single kmov from the comparison's mask register on AVX-512: 9-10% faster
// traversal than the byte trick below (RESULTS.md). Elsewhere on a little-endian device: the lanes narrowed to bytes
// (lane i in byte i), one bit kept per byte, and a multiply that adds the eight bytes into the top one (the bits are
// distinct, so nothing carries); 2-3% faster on PoCL than OR-ing the halves, the portable fallback.
inline uint lane_mask(int8 lanes) {
#if defined(__AVX__) && defined(__clang__)
  return (uint)__builtin_ia32_movmskps256(as_float8(lanes));
#elif defined(__ENDIAN_LITTLE__)
  ulong bytes = as_ulong(convert_char8(lanes)) & 0x8040201008040201ul;
  return (uint)((bytes * 0x0101010101010101ul) >> 56);
#else
  int8 bits = lanes & (int8)(1, 2, 4, 8, 16, 32, 64, 128);
  int4 b4 = bits.lo | bits.hi;
  int2 b2 = b4.lo | b4.hi;
  return (uint)(b2.x | b2.y);
#endif
}

// Index of the lowest set bit of a non-zero mask (ctz is OpenCL 2.0; this is 1.2). Clang's builtin is one tzcnt where
// the device has it; the portable form isolates the bit and counts from the top.
inline int lowest_bit(uint mask) {
#ifdef __clang__
  return __builtin_ctz(mask);
#else
  return 31 - (int)clz(mask & (0u - mask));
#endif
}

#define SEL_MIN(a, b) ((a) < (b) ? (a) : (b))
#define SEL_MAX(a, b) ((a) > (b) ? (a) : (b))

// Which of the eight children the ray enters before t_far, and at what distance. The slab distances use explicit
// fma (contraction is off in every program): one instruction each, and conservative enough for the box test.
inline uint node_hit_mask(__global const float8* node, const RayPrecomp* r, float t_min, float t_far, float8* t_entry) {
  float8 nx = fma(node[r->near_x], (float8)(r->inv_dir.x), (float8)(-r->org_inv.x));
  float8 fx = fma(node[r->near_x ^ 1], (float8)(r->inv_dir.x), (float8)(-r->org_inv.x));
  float8 ny = fma(node[r->near_y], (float8)(r->inv_dir.y), (float8)(-r->org_inv.y));
  float8 fy = fma(node[r->near_y ^ 1], (float8)(r->inv_dir.y), (float8)(-r->org_inv.y));
  float8 nz = fma(node[r->near_z], (float8)(r->inv_dir.z), (float8)(-r->org_inv.z));
  float8 fz = fma(node[r->near_z ^ 1], (float8)(r->inv_dir.z), (float8)(-r->org_inv.z));
  float8 tn = SEL_MAX(SEL_MAX(nx, ny), SEL_MAX(nz, (float8)(t_min)));
  float8 tf = SEL_MIN(SEL_MIN(fx, fy), SEL_MIN(fz, (float8)(t_far)));
  *t_entry = tn;
  return lane_mask(tn <= tf);
}

// The watertight test on eight triangles at once. Returns the lanes hit within (t_min, t_max) and their distances and
// barycentrics (u for v1, v for v2).
inline uint block_hit_mask(__global const float8* block, const RayPrecomp* r, float t_min, float t_max, float8* t_out,
                           float8* u_out, float8* v_out) {
  float8 ax = block[r->kx] - r->org_kx, ay = block[r->ky] - r->org_ky, az = block[r->kz] - r->org_kz;
  float8 bx = block[3 + r->kx] - r->org_kx, by = block[3 + r->ky] - r->org_ky, bz = block[3 + r->kz] - r->org_kz;
  float8 cx = block[6 + r->kx] - r->org_kx, cy = block[6 + r->ky] - r->org_ky, cz = block[6 + r->kz] - r->org_kz;
  ax = ax - r->shear_x * az;
  ay = ay - r->shear_y * az;
  bx = bx - r->shear_x * bz;
  by = by - r->shear_y * bz;
  cx = cx - r->shear_x * cz;
  cy = cy - r->shear_y * cz;
  float8 eu = cx * by - cy * bx;  // weight of v0
  float8 ev = ax * cy - ay * cx;  // weight of v1
  float8 ew = bx * ay - by * ax;  // weight of v2
  int8 mixed = ((eu < 0.0f) | (ev < 0.0f) | (ew < 0.0f)) & ((eu > 0.0f) | (ev > 0.0f) | (ew > 0.0f));
  float8 det = eu + ev + ew;
  float8 t_scaled = (eu * az + ev * bz + ew * cz) * r->shear_z;
  float8 abs_det = fabs(det);
  // Compare t * det against the range without dividing: flip t's sign with det's.
  float8 t_signed = as_float8(as_int8(t_scaled) ^ (as_int8(det) & (int8)(0x80000000)));
  int8 ok = ~mixed & (det != 0.0f) & (t_signed > t_min * abs_det) & (t_signed < t_max * abs_det);
  uint mask = lane_mask(ok);
  if (mask) {
    float8 inv_det = 1.0f / det;
    *t_out = t_scaled * inv_det;
    *u_out = ev * inv_det;
    *v_out = ew * inv_det;
  }
  return mask;
}

typedef struct {
  float t;
  float u, v;
  int prim;
} TraceHit;

#if HAS_ALPHA_MASK
// glTF's alpha mode MASK: a surface whose alpha (base colour factor times texture) is below its material's cutoff is
// a hole, for every kind of ray (a leaf is a leaf, not a quad). Alpha mode BLEND is made unbiased by hashed
// transparency: each point of the surface is a hole with probability 1 - alpha, by a hash of where it is (triangle
// and barycentrics), so every ray that reaches a point (camera, shadow, record, path) agrees on it and the same input
// gives the same bits; over a pixel's samples, a light's area or a record's rays, a fraction alpha is seen.
inline bool is_hole(BVH_ARGS, int prim, float u, float v) {
  __global const TriangleShading* t = triangles + prim;
  __global const Material* m = materials + t->material;
  if (!(m->alpha_cutoff > 0.0f) && !m->alpha_blend) return false;
  float alpha = m->base_color[3];
#if HAS_TEXTURES
  if (m->base_color_texture >= 0) {
    float w = 1.0f - u - v;
    float2 uv = w * vload2(0, t->uv0) + u * vload2(0, t->uv1) + v * vload2(0, t->uv2);
    alpha *= sample_texture(textures, texels, m->base_color_texture, uv).w;
  }
#endif
  if (m->alpha_blend) return random01((uint)prim, as_uint(u), as_uint(v)) >= alpha;
  return alpha < m->alpha_cutoff;
}

// The lanes of a block's hit mask that did not land in a hole.
inline uint solid_lanes(BVH_ARGS, uint mask, __global const float8* block, float8 uu, float8 vv) {
  float us[8], vs[8];
  int prims[8];
  vstore8(uu, 0, us);
  vstore8(vv, 0, vs);
  vstore8(as_int8(block[9]), 0, prims);
  uint solid = mask;
  while (mask) {
    int i = lowest_bit(mask);
    mask &= mask - 1;
    if (is_hole(BVH, prims[i], us[i], vs[i])) solid &= ~(1u << i);
  }
  return solid;
}
#endif

// Visits the BVH for one ray. ANY_HIT stops at the first hit within range (shadow rays); otherwise the closest hit wins.
// Returns whether anything was hit; on a closest hit *hit holds it.
inline bool bvh_trace(BVH_ARGS, const RayPrecomp* r, float t_min, float t_max, bool any_hit, TraceHit* hit) {
  // A stack entry is a subtree's entry distance in the high word and its reference in the low word: one load and one
  // store per move. The distance's float bits order like the distances only where they are not negative, so entries
  // behind the origin (a negative t_min) are kept as +0: never culled, and visited in lane order among themselves.
  ulong stack[BVH_STACK_SIZE];
  int sp = 0;
  int ref = 0;  // the root is always an inner node
  bool found = false;
  hit->prim = -1;
  hit->t = t_max;
  for (;;) {
    if (ref >= 0) {
      __global const float8* node = nodes + (size_t)ref * NODE_ROWS;
      float8 t_entry;
      uint mask = node_hit_mask(node, r, t_min, t_max, &t_entry);
      if (mask) {
        uint te[8];
        int refs[8];
        vstore8(as_uint8(SEL_MAX(t_entry, (float8)(0.0f))), 0, te);
        vstore8(as_int8(node[6]), 0, refs);
        int i0 = lowest_bit(mask);
        mask &= mask - 1;
        if (!mask) {
          ref = refs[i0];
          continue;
        }
        if (any_hit) {  // any occluder ends the ray, wherever it lies: visit the children in lane order
          stack[sp++] = (uint)refs[i0];
          while (mask) {
            int i = lowest_bit(mask);
            mask &= mask - 1;
            stack[sp++] = (uint)refs[i];
          }
          ref = (int)(uint)stack[--sp];
          continue;
        }
        int i1 = lowest_bit(mask);
        mask &= mask - 1;
        if (!mask) {  // two children: descend into the nearer, keep the farther
          int near_i = te[i0] <= te[i1] ? i0 : i1;
          int far_i = near_i == i0 ? i1 : i0;
          stack[sp++] = ((ulong)te[far_i] << 32) | (uint)refs[far_i];
          ref = refs[near_i];
          continue;
        }
        // Three or more: push all, sorted so that the nearest ends on top.
        int base = sp;
        stack[sp++] = ((ulong)te[i0] << 32) | (uint)refs[i0];
        stack[sp++] = ((ulong)te[i1] << 32) | (uint)refs[i1];
        while (mask) {
          int i = lowest_bit(mask);
          mask &= mask - 1;
          stack[sp++] = ((ulong)te[i] << 32) | (uint)refs[i];
        }
        for (int a = base + 1; a < sp; ++a) {
          ulong entry = stack[a];
          uint ta = (uint)(entry >> 32);
          int b = a - 1;
          while (b >= base && (uint)(stack[b] >> 32) < ta) {
            stack[b + 1] = stack[b];
            --b;
          }
          stack[b + 1] = entry;
        }
        ref = (int)(uint)stack[--sp];
        continue;
      }
    } else {
      int leaf = ~ref;
      int first = leaf >> 2;
      int count = (leaf & 3) + 1;
      for (int b = 0; b < count; ++b) {
        __global const float8* block = blocks + (size_t)(first + b) * BLOCK_ROWS;
        float8 tt, uu, vv;
        uint mask = block_hit_mask(block, r, t_min, t_max, &tt, &uu, &vv);
#if HAS_ALPHA_MASK
        if (mask) mask = solid_lanes(BVH, mask, block, uu, vv);
#endif
        if (mask) {
          if (any_hit) return true;
          float ts[8], us[8], vs[8];
          int prims[8];
          vstore8(tt, 0, ts);
          vstore8(uu, 0, us);
          vstore8(vv, 0, vs);
          vstore8(as_int8(block[9]), 0, prims);
          while (mask) {
            int i = lowest_bit(mask);
            mask &= mask - 1;
            if (ts[i] < t_max) {
              t_max = ts[i];
              hit->t = ts[i];
              hit->u = us[i];
              hit->v = vs[i];
              hit->prim = prims[i];
              found = true;
            }
          }
        }
      }
    }
    // Pop the next subtree that may still hold something nearer than the current hit.
    const uint t_max_bits = as_uint(t_max);
    do {
      if (sp == 0) return found;
      --sp;
    } while ((uint)(stack[sp] >> 32) > t_max_bits);
    ref = (int)(uint)stack[sp];
  }
}

#endif
