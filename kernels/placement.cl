// Record placement, coarse to fine (ALGORITHM.md section 7), and neighbour clamping of radii (Křivánek et al. 2006).
// Only counts cross to the host: candidates are compacted on the device.
#include "cache.h"

// Coverage on the grid of the given spacing: 1 where some record is usable (w > 1/a and not in front). The same test
// as the splat's, but only on the grid pixels placement looks at, and a plain store (every writer stores 1), so a
// level costs about 1/spacing^2 of a splat.
__kernel void mark_covered(__global const CacheRecord* records, uint first_record, uint record_count, float accuracy,
                           __global const GBufferSample* gbuffer, __global const CameraParams* camera, int spacing,
                           __global uchar* covered) {
  if (get_global_id(0) >= record_count) return;
  __global const CacheRecord* rec = records + first_record + get_global_id(0);
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float radius = rec->radius;
  PixelRect rect = sphere_footprint(camera, pk, accuracy * radius);
  int x0 = (rect.x0 + spacing - 1) / spacing * spacing, y0 = (rect.y0 + spacing - 1) / spacing * spacing;
  for (int y = y0; y <= rect.y1; y += spacing) {
    for (int x = x0; x <= rect.x1; x += spacing) {
      uint pixel = (uint)(y * camera->width + x);
      if (covered[pixel]) continue;  // another record got there first: reading is cheaper than writing again
      __global const GBufferSample* g = gbuffer + pixel;
      if (g->triangle < 0) continue;
      float3 p = vload3(0, g->position), n = vload3(0, g->normal);
      if (record_usable(ward_weight(p, n, pk, nk, radius), accuracy, p, n, pk, nk, radius)) covered[pixel] = 1;
    }
  }
}

// Pixels on the grid of the given spacing that see geometry and are not covered become candidates.
// A pixel that already holds a record never gets a second one.
__kernel void find_uncovered(__global const GBufferSample* gbuffer, __global const uchar* covered,
                             __global const int* record_at_pixel, int width, int height, int spacing,
                             __global uint* candidates, __global uint* candidate_count) {
  int x = get_global_id(0) * spacing, y = get_global_id(1) * spacing;
  if (x >= width || y >= height) return;
  uint pixel = (uint)(y * width + x);
  if (gbuffer[pixel].triangle < 0 || covered[pixel] || record_at_pixel[pixel] >= 0) return;
  candidates[atomic_inc(candidate_count)] = pixel;
}

// Tiles of NEW_TILE x NEW_TILE pixels: which ones hold a record of the newest batch (older records need only look there).
#define NEW_TILE 16

__kernel void mark_records(__global const CacheRecord* records, uint first, uint count, __global int* record_at_pixel,
                           int width, __global uchar* new_in_tile) {
  uint i = get_global_id(0);
  if (i >= count) return;
  int pixel = records[first + i].pixel;
  record_at_pixel[pixel] = (int)(first + i);
  int tiles_x = (width + NEW_TILE - 1) / NEW_TILE;
  new_in_tile[(pixel / width) / NEW_TILE * tiles_x + (pixel % width) / NEW_TILE] = 1;
}

// R_i <= R_j + |P_i - P_j| for every record j within R_i of record i (only those can lower R_i), for the pairs with at
// least one record of the newest batch (records first_new and up): each pair is clamped once, when the later of the two
// appears, as in Křivánek et al. 2006, without a transitive cascade through older records. Reads the radii and writes
// new ones elsewhere, so the result does not depend on the order work-items run in. Without clamp_older only the new
// records are clamped: the last rounds of placement use that, so that shrinking old records cannot uncover pixels again.
__kernel void clamp_neighbours(__global const CacheRecord* records, uint record_count, uint first_new, int clamp_older,
                               __global const int* record_at_pixel, __global const uchar* new_in_tile,
                               __global const CameraParams* camera, float min_spacing, __global float* clamped_radius) {
  uint i = get_global_id(0);
  if (i >= record_count) return;
  float3 pi = vload3(0, records[i].position);
  float radius = records[i].radius;
  if (i < first_new && !clamp_older) {
    clamped_radius[i] = radius;
    return;
  }
  PixelRect rect = sphere_footprint(camera, pi, radius);
  float clamped = radius;
  bool old = i < first_new;
  int tiles_x = (camera->width + NEW_TILE - 1) / NEW_TILE;
  for (int ty = rect.y0 / NEW_TILE; ty <= rect.y1 / NEW_TILE; ++ty) {
    for (int tx = rect.x0 / NEW_TILE; tx <= rect.x1 / NEW_TILE; ++tx) {
      if (old && !new_in_tile[ty * tiles_x + tx]) continue;  // an old record only pairs with new ones
      int y_end = min(rect.y1, ty * NEW_TILE + NEW_TILE - 1), x_end = min(rect.x1, tx * NEW_TILE + NEW_TILE - 1);
      for (int y = max(rect.y0, ty * NEW_TILE); y <= y_end; ++y) {
        for (int x = max(rect.x0, tx * NEW_TILE); x <= x_end; ++x) {
          int j = record_at_pixel[y * camera->width + x];
          if (j < 0 || (uint)j == i || (old && (uint)j < first_new)) continue;
          clamped = fmin(clamped, records[j].radius + distance(pi, vload3(0, records[j].position)));
        }
      }
    }
  }
  // The screen-space minimum still holds: a neighbour seen at another depth may have a smaller one.
  clamped_radius[i] = fmax(clamped, fmin(radius, min_spacing * records[i].pixel_size));
}

__kernel void apply_radii(__global CacheRecord* records, uint record_count, __global const float* clamped_radius) {
  uint i = get_global_id(0);
  if (i >= record_count) return;
  records[i].radius = clamped_radius[i];
}
