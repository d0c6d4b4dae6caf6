// The light guide's clusters made on the device from its photons (host/passes/guide_cluster_pass.h): the host's
// cluster_photons (host/cache/light_guide.cpp) bit for bit, by the same double-precision operations in the same order,
// so only built for a device with doubles (cl_khr_fp64); on another the host makes them. The steps:
//   bin_guide_photons      each photon's bin (grid cell and facing) and its weight, the luminance of its flux;
//   (a stable sort of the photons by bin: GridSortPass::order_by_bucket)
//   sum_guide_bins         each bin's flux, summed over its photons in their order, as the host sums it;
//   join_guide_bins        bins joined into regions: each takes the lowest label among itself and the neighbours it
//                          joins, again until no label changes; a region's label is then its lowest bin, whatever the
//                          order work-items ran in (the host's union-find keeps the same partition);
//   (a stable sort of the photons by region)
//   sum_guide_regions      each region's sums over its photons in their order, as the host's loop adds them;
//   (a scan of the regions that hold light, into a list)
//   write_guide_clusters   each region's rank (brightest first, ties by position), the first max_clusters written.
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#include "host_device.h"
#include "shared_types.h"

// The bins (GUIDE_BIN_COUNT) are in shared_types.h, beside the grid the host bins photons on.
#define GUIDE_NO_BIN 0xffffffffu

inline double luminance_double(double r, double g, double b) {
  return RC_LUMINANCE_R * r + RC_LUMINANCE_G * g + RC_LUMINANCE_B * b;
}

inline double3 load_double3(__global const float* v) { return (double3)((double)v[0], (double)v[1], (double)v[2]); }

inline uint bin_index(int3 cell, uint facing) {
  return (((uint)(cell.x + 1) * GUIDE_CELL_SPAN + (uint)(cell.y + 1)) * GUIDE_CELL_SPAN + (uint)(cell.z + 1)) * 6u +
         facing;
}

// Photon i's bin (GUIDE_BIN_COUNT for none: it left the scene or carries no light) and weight.
__kernel void bin_guide_photons(__global const PhotonHit* photons, uint photon_count, __global uint* photon_bin,
                                __global double* photon_weight) {
  const uint i = get_global_id(0);
  if (i >= photon_count) return;
  __global const PhotonHit* p = photons + i;
  const double w = luminance_double((double)p->flux[0], (double)p->flux[1], (double)p->flux[2]);
  photon_weight[i] = w;
  if (!p->hit || !(w > 0.0) || !isfinite(w)) {
    photon_bin[i] = GUIDE_BIN_COUNT;
    return;
  }
  int c[3];
  for (int a = 0; a < 3; ++a)
    c[a] = clamp((int)floor(((double)p->position[a] + 1.0) * 0.5 * GUIDE_GRID_CELLS), -1, GUIDE_GRID_CELLS);
  const double3 m = fabs(load_double3(p->normal));
  const double n[3] = {(double)p->normal[0], (double)p->normal[1], (double)p->normal[2]};
  const uint axis = m.x >= m.y && m.x >= m.z ? 0u : (m.y >= m.z ? 1u : 2u);
  photon_bin[i] = bin_index((int3)(c[0], c[1], c[2]), 2u * axis + (n[axis] < 0.0 ? 1u : 0u));
}

// Bin b's flux (the weights of its photons, in their order) and its first label (itself; GUIDE_NO_BIN: empty).
__kernel void sum_guide_bins(__global const uint* order, __global const uint* bin_starts,
                             __global const double* photon_weight, __global double* bin_flux,
                             __global uint* labels) {
  const uint b = get_global_id(0);
  if (b >= GUIDE_BIN_COUNT) return;
  double flux = 0.0;
  for (uint k = bin_starts[b]; k < bin_starts[b + 1]; ++k) flux += photon_weight[order[k]];
  bin_flux[b] = flux;
  labels[b] = bin_starts[b + 1] > bin_starts[b] ? b : GUIDE_NO_BIN;
}

// Whether bins a and b join (the host's test, made from either side: its union-find joins them when either passes).
#define GUIDE_REGION_FLUX_RATIO 8.0
inline bool bins_join(double a, double b) {
  const double ab = a / b, ba = b / a;
  return !(ab > GUIDE_REGION_FLUX_RATIO || ab < 1.0 / GUIDE_REGION_FLUX_RATIO) ||
         !(ba > GUIDE_REGION_FLUX_RATIO || ba < 1.0 / GUIDE_REGION_FLUX_RATIO);
}

// One round: bin b takes the lowest label of its label's own label and of the neighbours it joins (26 cells around,
// the same facing); *changed is set when any label fell.
__kernel void join_guide_bins(__global const double* bin_flux, volatile __global uint* labels,
                              volatile __global uint* changed) {
  const uint b = get_global_id(0);
  if (b >= GUIDE_BIN_COUNT || labels[b] == GUIDE_NO_BIN) return;
  const uint facing = b % 6u, cell = b / 6u;
  const int3 c = (int3)((int)(cell / (GUIDE_CELL_SPAN * GUIDE_CELL_SPAN)) - 1,
                        (int)(cell / GUIDE_CELL_SPAN % GUIDE_CELL_SPAN) - 1, (int)(cell % GUIDE_CELL_SPAN) - 1);
  uint lowest = labels[b];
  lowest = min(lowest, labels[lowest]);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const int3 n = c + (int3)(dx, dy, dz);
        if (any(n < (int3)(-1)) || any(n > (int3)(GUIDE_GRID_CELLS))) continue;
        const uint nb = bin_index(n, facing);
        const uint label = labels[nb];
        if (label != GUIDE_NO_BIN && bins_join(bin_flux[b], bin_flux[nb])) lowest = min(lowest, label);
      }
  if (lowest < labels[b]) {
    atomic_min(labels + b, lowest);
    *changed = 1u;
  }
}

// Photon i's region: its bin's label (GUIDE_BIN_COUNT for none).
__kernel void label_guide_photons(__global const uint* photon_bin, uint photon_count, __global const uint* labels,
                                  __global uint* photon_region) {
  const uint i = get_global_id(0);
  if (i >= photon_count) return;
  const uint bin = photon_bin[i];
  photon_region[i] = bin == GUIDE_BIN_COUNT ? GUIDE_BIN_COUNT : labels[bin];
}

// Region r's sums over its photons in their order, then its centroid and spread, as the host's three loops make them;
// has_light[r]: whether it holds any (a region with weight > 0).
__kernel void sum_guide_regions(__global const PhotonHit* photons, __global const double* photon_weight,
                                __global const uint* order, __global const uint* region_starts,
                                __global double* regions, __global uint* has_light) {
  const uint r = get_global_id(0);
  if (r >= GUIDE_BIN_COUNT) return;
  double3 flux = (double3)(0.0), position = (double3)(0.0), normal = (double3)(0.0);
  double weight = 0.0, square_distances = 0.0;
  const uint first = region_starts[r], end = region_starts[r + 1];
  for (uint k = first; k < end; ++k) {
    __global const PhotonHit* p = photons + order[k];
    const double w = photon_weight[order[k]];
    flux += load_double3(p->flux);
    weight += w;
    position += w * load_double3(p->position);
    normal += w * load_double3(p->normal);
  }
  if (weight > 0.0) position /= weight;
  for (uint k = first; k < end; ++k) {
    __global const PhotonHit* p = photons + order[k];
    const double3 offset = load_double3(p->position) - position, squares = offset * offset;
    square_distances += photon_weight[order[k]] * (squares.x + squares.y + squares.z);
  }
  __global double* out = regions + (size_t)r * GUIDE_REGION_DOUBLES;
  out[0] = flux.x, out[1] = flux.y, out[2] = flux.z;
  out[3] = position.x, out[4] = position.y, out[5] = position.z;
  out[6] = normal.x, out[7] = normal.y, out[8] = normal.z;
  out[9] = weight;
  out[10] = square_distances;
  has_light[r] = weight > 0.0 ? 1u : 0u;
}

// Region r (with light) at its place in the list of such regions.
__kernel void list_guide_regions(__global const uint* has_light, __global const uint* places, __global uint* list) {
  const uint r = get_global_id(0);
  if (r < GUIDE_BIN_COUNT && has_light[r]) list[places[r]] = r;
}

// Whether region a comes before region b: brighter first, ties by position (the host's sort).
inline bool region_before(__global const double* a, __global const double* b) {
  if (a[9] != b[9]) return a[9] > b[9];
  return a[3] != b[3] ? a[3] < b[3] : (a[4] != b[4] ? a[4] < b[4] : a[5] < b[5]);
}

// Listed region i's rank among the region_count listed; the first max_clusters become clusters at their ranks. The
// radius: twice the flux-weighted RMS distance from the centroid, never less than a sixteenth of a cell.
__kernel void write_guide_clusters(__global const double* regions, __global const uint* list, uint region_count,
                                   uint max_clusters, __global GuideCluster* clusters) {
  const uint i = get_global_id(0);
  if (i >= region_count) return;
  __global const double* r = regions + (size_t)list[i] * GUIDE_REGION_DOUBLES;
  uint rank = 0;
  for (uint j = 0; j < region_count; ++j)
    if (j != i && region_before(regions + (size_t)list[j] * GUIDE_REGION_DOUBLES, r)) ++rank;
  if (rank >= max_clusters) return;
  GuideCluster c;
  const double weight = r[9];
  for (int a = 0; a < 3; ++a) {
    c.centre[a] = (float)r[3 + a];
    c.flux[a] = (float)r[a];
    c.normal[a] = (float)(r[6 + a] / weight);
  }
  c.radius = (float)fmax(2.0 * sqrt(r[10] / weight), (2.0 / GUIDE_GRID_CELLS) / 16.0);
  c.pad0 = c.pad1 = 0.0f;
  clusters[rank] = c;
}
