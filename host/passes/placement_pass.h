// Coarse-to-fine record placement on the device and neighbour clamping of radii (kernels/placement.cl): owns the
// candidate list, the per-level coverage and the map from pixels to the records placed on them.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "passes/gbuffer_pass.h"
#include "passes/scan_pass.h"

namespace rcsplat {

class PlacementPass {
 public:
  PlacementPass(GpuContext& gpu, const GBufferView& gbuffer);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // A new frame (a pass kept across frames, render/indirect.h): no record sits anywhere yet; the buffers are kept
  // while the frame's size is.
  void begin(const GBufferView& gbuffer);

  // Compacts the pixels with geometry on the grid of this spacing that hold no record and that no record among
  // 0 .. record_count - 1 reaches (Ward weight above 1/a, not in front) into candidates(), tile by tile of
  // CANDIDATE_TILE cells a side (kernels/placement.cl candidate_cell); returns their count. With
  // unchanged_before = n, records 0 .. n - 1 kept their radii since the last call at this spacing: their coverage is
  // kept.
  uint32_t find_uncovered(const cl::Buffer& records, uint32_t record_count, float accuracy, int spacing,
                          uint32_t unchanged_before);
  const cl::Buffer& candidates() const { return candidates_; }

  // Records 0 .. count - 1, kept from earlier frames, fitted to this frame's view (kernels/placement.cl
  // fit_kept_records): radii clamped again to [min, max] footprints here, each on the pixel it projects to, or on
  // none. Then mark(records, 0, count) seats them.
  // harmonic_radius: a record's own radius is its harmonic distance (no --hessian-error).
  void fit_kept(const cl::Buffer& records, uint32_t count, float min_radius_pixels, float max_radius_pixels,
                bool harmonic_radius);
  // Records first .. first + count - 1 now sit on their pixels (those whose pixel is -1 sit nowhere).
  void mark(const cl::Buffer& records, uint32_t first, uint32_t count);
  // R_i <= R_j + |P_i - P_j| over records 0 .. count - 1, for pairs that involve a record first_new or later; older
  // records keep their radii unless clamp_older. Radii stay at least min_radius_pixels footprints.
  void clamp_neighbours(const cl::Buffer& records, uint32_t count, uint32_t first_new, bool clamp_older,
                        float min_radius_pixels);

  std::vector<int32_t> record_at_pixel();  // record index, -1 where none sits
  const cl::Buffer& record_at_pixel_buffer() const { return record_map_; }

 private:
  static constexpr const char* kProgram = "placement.cl";  // its kernels' file
  GpuContext& gpu_;
  GBufferView gbuffer_;
  NamedKernel covered_kernel_, flag_, compact_, mark_, clamp_, apply_, fit_;
  ScanPass scan_;  // the candidates' places, in pixel order
  cl::Buffer candidates_, count_, record_map_, radii_, covered_, new_in_tile_, flags_, places_;
  size_t tiles_ = 0;
  size_t radii_capacity_ = 0;
  size_t flags_capacity_ = 0, places_capacity_ = 0;  // cells
  int record_grid_ = 0;  // the finest placement grid searched so far: every record sits on one of its pixels
};

}  // namespace rcsplat
