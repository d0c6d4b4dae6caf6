// Record placement, coarse to fine (docs/ALGORITHM.md section 7), and neighbour clamping of radii (Křivánek et al. 2006).
// Only counts cross to the host: candidates are compacted on the device.
#include "footprint.h"
#include "scene_args.h"

// The first multiple of the grid at or after v (v >= 0).
inline int grid_ceil(int v, int grid) { return (v + grid - 1) / grid * grid; }

// Coverage on the grid of the given spacing: 1 where some record is usable (w > 1/a and not in front). The same test
// as the splat's, but only on the grid pixels placement looks at, and a plain store (every writer stores 1), so a
// level costs about 1/spacing^2 of a splat.
__kernel void mark_covered(GBUFFER_ARGS, __global const CacheRecord* records, PlacementParams params,
                           __global uchar* covered) {
  if (get_global_id(0) >= params.record_count) return;
  const float accuracy = params.accuracy;
  const int spacing = params.spacing;
  __global const CacheRecord* rec = records + params.first_record + get_global_id(0);
  float3 pk = vload3(0, rec->position), nk = vload3(0, rec->normal);
  float radius = rec->radius;
  float3 tk, bk;
  tangent_frame(nk, &tk, &bk);
  PixelRect rect = sphere_footprint(camera, pk, accuracy * radius);
  int x0 = grid_ceil(rect.x0, spacing), y0 = grid_ceil(rect.y0, spacing);
  for (int y = y0; y <= rect.y1; y += spacing) {
    for (int x = x0; x <= rect.x1; x += spacing) {
      uint pixel = (uint)(y * camera->width + x);
      if (covered[pixel]) continue;  // another record got there first: reading is cheaper than writing again
      __global const GBufferSample* g = gbuffer + pixel;
      if (g->triangle < 0) continue;
      float3 p = vload3(0, g->position), n = vload3(0, g->normal);
      if (record_reaches(rec, tk, bk, ward_weight(p, n, pk, nk, radius), accuracy, p, n, pk, nk, radius)) covered[pixel] = 1;
    }
  }
}

// Candidates are listed tile by tile (CANDIDATE_TILE x CANDIDATE_TILE cells of the placement grid; tiles row by row,
// cells row by row within a tile): neighbours in the list are neighbours in the image, whose record rays a work-group
// of the record pass then traces together (the grid's rows made Cornell's records 5% slower on PoCL). The grid is
// padded to whole tiles; a cell's place in that order:
inline uint candidate_cell(uint gx, uint gy, uint tiles_x) {
  const uint tile = (gy / CANDIDATE_TILE) * tiles_x + gx / CANDIDATE_TILE;
  return (tile * CANDIDATE_TILE + gy % CANDIDATE_TILE) * CANDIDATE_TILE + gx % CANDIDATE_TILE;
}

// Pixels on the grid of the given spacing that see geometry and are not covered become candidates: flags[cell] is 1
// for them, 0 for the other cells, padding included (tiles_x, tiles_y: the padded grid's tiles). A pixel that already
// holds a record never gets a second one.
__kernel void flag_uncovered(GBUFFER_ARGS, __global const uchar* covered, __global const int* record_at_pixel,
                             PlacementParams params, uint tiles_x, uint tiles_y, __global uint* flags) {
  const uint gx = get_global_id(0), gy = get_global_id(1);
  if (gx >= tiles_x * CANDIDATE_TILE || gy >= tiles_y * CANDIDATE_TILE) return;
  const int x = (int)gx * params.spacing, y = (int)gy * params.spacing;
  bool candidate = false;
  if (x < camera->width && y < camera->height) {
    const uint pixel = (uint)(y * camera->width + x);
    candidate = gbuffer[pixel].triangle >= 0 && !covered[pixel] && record_at_pixel[pixel] < 0;
  }
  flags[candidate_cell(gx, gy, tiles_x)] = candidate ? 1u : 0u;
}

// The flagged cells' pixels, in the cells' order (the same whatever order work items run in), at the places the
// flags' exclusive scan gives them; *candidate_count: how many.
__kernel void compact_uncovered(__global const CameraParams* camera, __global const uint* flags,
                                __global const uint* places, uint cells, uint tiles_x, PlacementParams params,
                                __global uint* candidates, __global uint* candidate_count) {
  const uint cell = get_global_id(0);
  if (cell >= cells) return;
  if (flags[cell]) {
    const uint tile = cell / (CANDIDATE_TILE * CANDIDATE_TILE), within = cell % (CANDIDATE_TILE * CANDIDATE_TILE);
    const uint gx = (tile % tiles_x) * CANDIDATE_TILE + within % CANDIDATE_TILE;
    const uint gy = (tile / tiles_x) * CANDIDATE_TILE + within / CANDIDATE_TILE;
    candidates[places[cell]] = gy * (uint)params.spacing * (uint)camera->width + gx * (uint)params.spacing;
  }
  if (cell == cells - 1) *candidate_count = places[cell] + flags[cell];
}

// Records first_record .. first_record + record_count - 1 (the newest batch) now sit on their pixels.
__kernel void mark_records(GBUFFER_ARGS, __global const CacheRecord* records, PlacementParams params,
                           __global int* record_at_pixel, __global uchar* new_in_tile) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  const int width = camera->width;
  int pixel = records[params.first_record + i].pixel;
  if (pixel < 0) return;  // a kept record this view does not see at its place (fit_kept_records)
  // Kept records may project to one pixel: the latest one sits there, whatever order work-items run in.
  atomic_max(record_at_pixel + pixel, (int)(params.first_record + i));
  int tiles_x = (width + PLACEMENT_TILE_SIZE - 1) / PLACEMENT_TILE_SIZE;
  new_in_tile[(pixel / width) / PLACEMENT_TILE_SIZE * tiles_x + (pixel % width) / PLACEMENT_TILE_SIZE] = 1;
}

// R_i <= R_j + |P_i - P_j| for every record j within R_i of record i (only those can lower R_i), for the pairs with at
// least one record of the newest batch (records first_new and up): each pair is clamped once, when the later of the two
// appears, as in Křivánek et al. 2006, without a transitive cascade through older records. Reads the radii and writes
// new ones elsewhere, so the result does not depend on the order work-items run in. Without clamp_older only the new
// records are clamped: the last rounds of placement use that, so that shrinking old records cannot uncover pixels again.
__kernel void clamp_neighbours(GBUFFER_ARGS, __global const CacheRecord* records, PlacementParams params,
                               __global const int* record_at_pixel, __global const uchar* new_in_tile,
                               __global float* clamped_radius) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  const uint first_new = params.first_new;
  const int grid = params.spacing;  // every record sits on a pixel of this grid: only those pixels are read
  const int clamp_older = params.clamp_older;
  float3 pi = vload3(0, records[i].position);
  float radius = records[i].radius;
  if (i < first_new && !clamp_older) {
    clamped_radius[i] = radius;
    return;
  }
  PixelRect rect = sphere_footprint(camera, pi, radius);
  float clamped = radius;
  bool old = i < first_new;
  int tiles_x = (camera->width + PLACEMENT_TILE_SIZE - 1) / PLACEMENT_TILE_SIZE;
  for (int ty = rect.y0 / PLACEMENT_TILE_SIZE; ty <= rect.y1 / PLACEMENT_TILE_SIZE; ++ty) {
    for (int tx = rect.x0 / PLACEMENT_TILE_SIZE; tx <= rect.x1 / PLACEMENT_TILE_SIZE; ++tx) {
      if (old && !new_in_tile[ty * tiles_x + tx]) continue;  // an old record only pairs with new ones
      int x_begin = tx * PLACEMENT_TILE_SIZE, y_begin = ty * PLACEMENT_TILE_SIZE;
      int y_end = min(rect.y1, y_begin + PLACEMENT_TILE_SIZE - 1), x_end = min(rect.x1, x_begin + PLACEMENT_TILE_SIZE - 1);
      for (int y = grid_ceil(max(rect.y0, y_begin), grid); y <= y_end; y += grid) {
        for (int x = grid_ceil(max(rect.x0, x_begin), grid); x <= x_end; x += grid) {
          int j = record_at_pixel[y * camera->width + x];
          if (j < 0 || (uint)j == i || (old && (uint)j < first_new)) continue;
          clamped = fmin(clamped, neighbour_radius_bound(pi, vload3(0, records[j].position), records[j].radius));
        }
      }
    }
  }
  clamped_radius[i] = neighbour_clamped_radius(radius, clamped, params.min_radius_pixels, records[i].pixel_size);
}

__kernel void apply_radii(__global CacheRecord* records, PlacementParams params, __global const float* clamped_radius) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  records[i].radius = clamped_radius[i];
}

// The pixel a kept record projects to in this view, where the G-buffer sees a point within a few pixel footprints of
// it (else -1: hidden or off screen, so it sits nowhere and blocks no placement), as the G-buffer's rays are made
// (kernels/gbuffer.cl).
inline int kept_record_pixel(GBUFFER_ARGS, float3 p, float pixel_size) {
  float3 d = p - vload3(0, camera->eye);
  float half_y = camera->orthographic ? camera->half_height : dot(d, vload3(0, camera->forward)) * camera->tan_half_fov_y;
  if (!(half_y > 0.0f)) return -1;
  float sx = dot(d, vload3(0, camera->right)) / (half_y * camera->aspect), sy = dot(d, vload3(0, camera->up)) / half_y;
  float fx = (sx + 1.0f) * 0.5f * (float)camera->width, fy = (1.0f - sy) * 0.5f * (float)camera->height;
  if (!(fx >= 0.0f && fx < (float)camera->width && fy >= 0.0f && fy < (float)camera->height)) return -1;
  int pixel = (int)fy * camera->width + (int)fx;
  __global const GBufferSample* g = gbuffer + pixel;
  if (g->triangle < 0 || distance(vload3(0, g->position), p) > 4.0f * pixel_size) return -1;
  return pixel;
}

// Records kept from earlier frames (render/kept_records.h), fitted to this view before placement: the reach clamps in
// pixel footprints (kernels/records.cl) apply again at this view's footprint, only where the radius has left them by
// more than 0.1% (a camera that barely moves leaves the radii as they are), a radius enlarged by an earlier view's
// minimum shrinks back toward the record's own, and each record sits on the pixel it projects to.
__kernel void fit_kept_records(GBUFFER_ARGS, __global CacheRecord* records, PlacementParams params) {
  uint i = get_global_id(0);
  if (i >= params.record_count) return;
  __global CacheRecord* rec = records + params.first_record + i;
  float3 p = vload3(0, rec->position);
  float pixel_size = pixel_world_size(camera, p);
  float radius = rec->radius, smallest = params.min_radius_pixels * pixel_size;
  float largest = params.max_radius_pixels * pixel_size;
  if (radius > 1.001f * largest) radius = largest;
  else if (radius < 0.999f * smallest) radius = smallest;
  // A radius the placing view's minimum reach enlarged past the record's own (Ward's harmonic distance) goes back to
  // what this view's clamps give it, as a record placed here would have it. (The Hessian's radius is not kept.)
  if (params.harmonic_radius) {
    float natural = clamp(rec->harmonic_distance, smallest, largest);
    if (radius > 1.001f * natural) radius = natural;
  }
  radius = radius > 0.0f ? radius : fmax(smallest, 1e-30f);
  if (radius > rec->radius) {
    // A reach grown for this view: the translation gradients bounded for it, as a record placed here would have them
    // (kernels/records.cl: E changes by at most E across the radius).
    // Rows are the axes, each an RGB triple: each channel's gradient is bounded alone (records.cl bound_gradient).
    float3 limit = vload3(0, rec->irradiance) / radius;
    float3 gx = vload3(0, rec->grad_translation), gy = vload3(1, rec->grad_translation),
           gz = vload3(2, rec->grad_translation);
    float3 length = sqrt(gx * gx + gy * gy + gz * gz);
    float3 scale = select((float3)(1.0f), limit / length, length > limit);
    gx *= scale;
    gy *= scale;
    gz *= scale;
    vstore3(select((float3)(0.0f), gx, isfinite(gx)), 0, rec->grad_translation);
    vstore3(select((float3)(0.0f), gy, isfinite(gy)), 1, rec->grad_translation);
    vstore3(select((float3)(0.0f), gz, isfinite(gz)), 2, rec->grad_translation);
  }
  rec->radius = radius;
  rec->pixel_size = pixel_size;
  rec->pixel = kept_record_pixel(GBUFFER, p, pixel_size);
}
