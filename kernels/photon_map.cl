// The photon map's per-photon estimates (kernels/photon_map.h), and the lookup on its own for tests.
#include "photon_map.h"
#include "sampling.h"

// A flux's sum over a disc and its first moments in the disc's tangent frame, about the disc's centre.
typedef struct {
  float3 sum, x, y;
} FluxMoments;

inline void add_flux(FluxMoments* m, float3 f, float dx, float dy) {
  m->sum += f;
  m->x += f * dx;
  m->y += f * dy;
}

// The area of the facing surface in a disc and its moments (first and second) about the disc's centre.
typedef struct {
  float area, x, y, xx, xy, yy;
} AreaMoments;

// The density at the disc's centre of a flux spread over the disc's surface, fitted as a linear function of position
// (a local linear density estimate): the mean density over the surface, flux / area, belongs to the surface's
// centroid, which lies off the centre wherever the disc reaches past an edge or into a corner, where the light
// changes most (a contact's light is brightest at the contact). The gradient g solves M g = flux's first moment about
// the centroid (M: the area's second moment about it, plus lambda = PHOTON_GRADIENT_RIDGE times a full disc's, so that
// a strip of surface does not extrapolate from noise), and the centre's value is mean - g . centroid, kept within
// [0, 2 mean]. A disc of fewer than PHOTON_FIT_SUPPORT photons (`support`) keeps its mean: three parameters fitted
// to a few photons follow their noise, and the clamp turns that noise into a bias (2% bright in a room lit through a
// gap: docs/NOTES.md "Issue 41: photons where they are scarce").
inline float3 density_at_centre(FluxMoments f, AreaMoments a, float r2, uint support) {
  if (!(a.area > 0.0f)) return (float3)(0.0f);
  float3 mean = f.sum / a.area;
  if ((float)support < PHOTON_FIT_SUPPORT) return mean;
  float cx = a.x / a.area, cy = a.y / a.area;
  float ridge = PHOTON_GRADIENT_RIDGE * a.area * r2 * 0.25f;
  float mxx = a.xx - a.area * cx * cx + ridge, mxy = a.xy - a.area * cx * cy, myy = a.yy - a.area * cy * cy + ridge;
  float det = mxx * myy - mxy * mxy;
  if (!(det > 0.0f)) return mean;
  float3 vx = f.x - f.sum * cx, vy = f.y - f.sum * cy;
  float3 gx = (myy * vx - mxy * vy) / det, gy = (mxx * vy - mxy * vx) / det;
  return clamp(mean - (gx * cx + gy * cy), 0.0f, 2.0f * mean);
}

// The estimates at the lookup grid's photon i (map_radiance[2i], [2i + 1]): the reflected light (photons' reflected
// flux: their surfaces' albedo averaged in) and the irradiance, both over pi, of every photon (the `all` grid) in the
// disc of radius all_grid.radius about it, per area of the facing surface the patches find in the same disc, fitted
// linearly (density_at_centre); map_radiance[2i].w: how many photons the disc held besides photon i itself, which
// is left out (a disc about a photon always holds it: counted, it would add one photon's worth, 1 / k of an estimate
// from k, where photons are few). The 3 x 3 x 3 cells around the point hold every photon and patch of the disc (cells
// are at least r wide). map_shallow: the same over the photons of landings below shallow_landings
// (PhotonMapGrids::shallow_landings). Work-item k makes photon estimate_order[k]'s: neighbours in space run together
// and read the same cells (kernels/grid_sort.cl coarse_cell_keys, or on the host host/cache/photon_map.h cell_order;
// 0.85x the kernel's time on PoCL, the same bits).
__kernel void estimate_photon_radiance(__global const PhotonHit* all_photons, __global const uint* all_buckets,
                                       PhotonMapParams all_grid, __global const SurfacePatch* patches,
                                       __global const uint* patch_buckets, PhotonMapParams patch_grid,
                                       __global const PhotonHit* map_photons, PhotonMapParams map,
                                       int shallow_landings, __global float4* map_radiance,
                                       __global float4* map_shallow, __global const uint* estimate_order) {
  if (get_global_id(0) >= map.photon_count) return;
  uint i = estimate_order[get_global_id(0)];
  float3 x = vload3(0, map_photons[i].position), n = vload3(0, map_photons[i].normal), t, b;
  tangent_frame(n, &t, &b);
  float r2 = all_grid.radius * all_grid.radius, half_thickness = PHOTON_DISC_HALF_THICKNESS * all_grid.radius;
  FluxMoments reflected = {0}, incident = {0}, shallow_reflected = {0}, shallow_incident = {0};
  uint support = 0;  // photons in the disc
  bool self_left_out = false;
  uint visited[27];
  uint visited_count = 0;
  int cx = photon_cell(x.x, all_grid.grid_origin[0], all_grid.cell_size);
  int cy = photon_cell(x.y, all_grid.grid_origin[1], all_grid.cell_size);
  int cz = photon_cell(x.z, all_grid.grid_origin[2], all_grid.cell_size);
  for (int c = 0; c < 27; ++c) {
    uint bucket = photon_bucket(cx + c % 3 - 1, cy + (c / 3) % 3 - 1, cz + c / 9 - 1, all_grid.bucket_count);
    if (!first_visit(bucket, visited, &visited_count)) continue;
    for (uint j = all_buckets[bucket]; j < all_buckets[bucket + 1u]; ++j) {
      float3 d = vload3(0, all_photons[j].position) - x;
      if (!in_disc(d, vload3(0, all_photons[j].normal), n, r2, half_thickness)) continue;
      if (!self_left_out && d.x == 0.0f && d.y == 0.0f && d.z == 0.0f) {
        self_left_out = true;
        continue;
      }
      float dx = dot(d, t), dy = dot(d, b);
      float3 fr = vload3(0, all_photons[j].flux), fi = vload3(0, all_photons[j].incident);
      ++support;
      add_flux(&reflected, fr, dx, dy);
      add_flux(&incident, fi, dx, dy);
      if (all_photons[j].landing < shallow_landings) {
        add_flux(&shallow_reflected, fr, dx, dy);
        add_flux(&shallow_incident, fi, dx, dy);
      }
    }
  }
  AreaMoments area = {0};
  visited_count = 0;
  cx = photon_cell(x.x, patch_grid.grid_origin[0], patch_grid.cell_size);
  cy = photon_cell(x.y, patch_grid.grid_origin[1], patch_grid.cell_size);
  cz = photon_cell(x.z, patch_grid.grid_origin[2], patch_grid.cell_size);
  for (int c = 0; c < 27 && patch_grid.photon_count; ++c) {
    uint bucket = photon_bucket(cx + c % 3 - 1, cy + (c / 3) % 3 - 1, cz + c / 9 - 1, patch_grid.bucket_count);
    if (!first_visit(bucket, visited, &visited_count)) continue;
    for (uint j = patch_buckets[bucket]; j < patch_buckets[bucket + 1u]; ++j) {
      float3 d = vload3(0, patches[j].position) - x;
      if (!in_disc(d, vload3(0, patches[j].normal), n, r2, half_thickness)) continue;
      float a = patches[j].area, dx = dot(d, t), dy = dot(d, b);
      area.area += a;
      area.x += a * dx;
      area.y += a * dy;
      area.xx += a * dx * dx;
      area.xy += a * dx * dy;
      area.yy += a * dy * dy;
    }
  }
  if (patch_grid.photon_count == 0u) {
    // No patches (a map built without the scene's surface): the disc is taken as full, the plain estimate.
    area.area = RC_PI * r2;
    area.xx = area.yy = area.area * r2 * 0.25f;
  }
  // An area below PHOTON_MIN_AREA_SHARE of the disc's (a lone sliver) is taken as that.
  area.area = fmax(area.area, PHOTON_MIN_AREA_SHARE * RC_PI * r2);
  map_radiance[2 * i] =
      (float4)(finite_or_zero(density_at_centre(reflected, area, r2, support) * RC_INV_PI), (float)support);
  map_radiance[2 * i + 1] = (float4)(finite_or_zero(density_at_centre(incident, area, r2, support) * RC_INV_PI), 0.0f);
  map_shallow[2 * i] =
      (float4)(finite_or_zero(density_at_centre(shallow_reflected, area, r2, support) * RC_INV_PI), 0.0f);
  map_shallow[2 * i + 1] =
      (float4)(finite_or_zero(density_at_centre(shallow_incident, area, r2, support) * RC_INV_PI), 0.0f);
}

// photon_map_radiance at query points (float4: xyz) with their normals, for tests: the reflected estimate.
__kernel void look_up_photon_radiance(PHOTON_MAP_ARGS, __global const float4* points, __global const float4* normals,
                                      uint point_count, __global float4* radiance) {
  uint i = get_global_id(0);
  if (i >= point_count) return;
  int nearest = photon_map_nearest(PHOTON_MAP, points[i].xyz, normals[i].xyz);
  radiance[i] = nearest < 0 ? (float4)(0.0f) : map_radiance[2 * nearest];
}
