#include "passes/placement_pass.h"

#include <algorithm>

#include "kernels/cache_math.h"

namespace rcsplat {
void PlacementPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); ScanPass::build_ahead(gpu); }
namespace {

size_t padded_to_tiles(size_t cells) { return (cells + CANDIDATE_TILE - 1) / CANDIDATE_TILE * CANDIDATE_TILE; }

}  // namespace

PlacementPass::PlacementPass(GpuContext& gpu, const GBufferView& gbuffer)
    : gpu_(gpu),
      gbuffer_(gbuffer),
      covered_kernel_(gpu.kernel(kProgram, "mark_covered")),
      flag_(gpu.kernel(kProgram, "flag_uncovered")),
      compact_(gpu.kernel(kProgram, "compact_uncovered")),
      mark_(gpu.kernel(kProgram, "mark_records")),
      clamp_(gpu.kernel(kProgram, "clamp_neighbours")),
      apply_(gpu.kernel(kProgram, "apply_radii")),
      fit_(gpu.kernel(kProgram, "fit_kept_records")),
      scan_(gpu) {
  begin(gbuffer);
}

void PlacementPass::begin(const GBufferView& gbuffer) {
  const size_t pixels = gbuffer.pixel_count();
  auto tiles = [](int n) { return size_t((n + PLACEMENT_TILE_SIZE - 1) / PLACEMENT_TILE_SIZE); };
  const size_t tiles_now = tiles(gbuffer.width) * tiles(gbuffer.height);
  if (!candidates_() || pixels != gbuffer_.pixel_count() || tiles_now != tiles_) {
    const size_t slots = std::max<size_t>(pixels, 1);
    candidates_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * sizeof(cl_uint), "placement candidates");
    record_map_ = gpu_.buffer(CL_MEM_READ_WRITE, slots * sizeof(cl_int), "placement");
    covered_ = gpu_.buffer(CL_MEM_READ_WRITE, slots, "placement covered");
    tiles_ = tiles_now;
    new_in_tile_ = gpu_.buffer(CL_MEM_READ_WRITE, std::max<size_t>(tiles_, 1), "placement new in tile");
  }
  if (!count_()) count_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, "placement");
  gbuffer_ = gbuffer;
  if (pixels) gpu_.queue().enqueueFillBuffer(record_map_, cl_int(-1), 0, pixels * sizeof(cl_int));
  record_grid_ = 0;
}

uint32_t PlacementPass::find_uncovered(const cl::Buffer& records, uint32_t record_count, float accuracy, int spacing,
                                       uint32_t unchanged_before) {
  PlacementParams params{};
  params.accuracy = accuracy;
  params.spacing = spacing;
  // Placement runs coarse to fine on power-of-two grids, so every record placed so far sits on this grid.
  record_grid_ = record_grid_ ? std::min(record_grid_, spacing) : spacing;
  if (!unchanged_before) gpu_.queue().enqueueFillBuffer(covered_, cl_uchar(0), 0, gbuffer_.pixel_count());
  if (record_count > unchanged_before) {
    params.first_record = unchanged_before;
    params.record_count = record_count - unchanged_before;
    gbuffer_.bind(covered_kernel_);
    covered_kernel_.set_buffer<CacheRecord>("records", records).set("params", params).set_buffer<cl_uchar>("covered", covered_);
    covered_kernel_.launch(params.record_count, gpu_.groups().per_record);
  }
  // Flagged, scanned and compacted rather than appended with an atomic counter: in a fixed order (tile by tile), the
  // records (and every sum over them in record order) are the same bits each run; an atomic hands places out in
  // whatever order the device runs work items, which differs from run to run on the same device.
  const size_t grid_x = padded_to_tiles((size_t(gbuffer_.width) + spacing - 1) / spacing);
  const size_t grid_y = padded_to_tiles((size_t(gbuffer_.height) + spacing - 1) / spacing), cells = grid_x * grid_y;
  // The finest grid's cells, padded to whole tiles (kernels/placement.cl candidate_cell).
  gpu_.reserve<cl_uint>(flags_, flags_capacity_, cells, "placement candidates");
  gpu_.reserve<cl_uint>(places_, places_capacity_, cells, "placement candidates");
  gbuffer_.bind(flag_);
  flag_.set_buffer<cl_uchar>("covered", covered_)
      .set_buffer<cl_int>("record_at_pixel", record_map_)
      .set("params", params)
      .set("tiles_x", cl_uint(grid_x / CANDIDATE_TILE))
      .set("tiles_y", cl_uint(grid_y / CANDIDATE_TILE))
      .set_buffer<cl_uint>("flags", flags_);
  flag_.launch_2d(grid_x, grid_y, gpu_.groups().tile_side);
  scan_.exclusive(flags_, uint32_t(cells), places_);
  compact_.set_buffer<CameraParams>("camera", gbuffer_.camera)
      .set_buffer<cl_uint>("flags", flags_)
      .set_buffer<cl_uint>("places", places_)
      .set("cells", cl_uint(cells))
      .set("tiles_x", cl_uint(grid_x / CANDIDATE_TILE))
      .set("params", params)
      .set_buffer<cl_uint>("candidates", candidates_)
      .set_buffer<cl_uint>("candidate_count", count_);
  gpu_.queue().enqueueFillBuffer(count_, cl_uint(0), 0, sizeof(cl_uint));  // an empty grid writes no count
  compact_.launch(cells, 256);
  return gpu_.download<cl_uint>(count_, 1)[0];
}

void PlacementPass::fit_kept(const cl::Buffer& records, uint32_t count, float min_radius_pixels,
                             float max_radius_pixels, bool harmonic_radius) {
  if (!count) return;
  PlacementParams params{};
  params.record_count = count;
  params.min_radius_pixels = min_radius_pixels;
  params.max_radius_pixels = max_radius_pixels;
  params.harmonic_radius = harmonic_radius ? 1 : 0;
  gbuffer_.bind(fit_);
  fit_.set_buffer<CacheRecord>("records", records).set("params", params);
  fit_.launch(count, gpu_.groups().per_item);
}

void PlacementPass::mark(const cl::Buffer& records, uint32_t first, uint32_t count) {
  if (!count) return;
  gpu_.queue().enqueueFillBuffer(new_in_tile_, cl_uchar(0), 0, tiles_);
  PlacementParams params{};
  params.first_record = first;
  params.record_count = count;
  gbuffer_.bind(mark_);
  mark_.set_buffer<CacheRecord>("records", records)
      .set("params", params)
      .set_buffer<cl_int>("record_at_pixel", record_map_)
      .set_buffer<cl_uchar>("new_in_tile", new_in_tile_);
  mark_.launch(count, gpu_.groups().per_item);
}

void PlacementPass::clamp_neighbours(const cl::Buffer& records, uint32_t count, uint32_t first_new, bool clamp_older,
                                     float min_radius_pixels) {
  if (!count) return;
  gpu_.reserve<float>(radii_, radii_capacity_, count, "placement radii");
  PlacementParams params{};
  params.record_count = count;
  params.first_new = first_new;
  params.clamp_older = clamp_older ? 1 : 0;
  params.min_radius_pixels = min_radius_pixels;
  params.spacing = std::max(record_grid_, 1);
  gbuffer_.bind(clamp_);
  clamp_.set_buffer<CacheRecord>("records", records)
      .set("params", params)
      .set_buffer<cl_int>("record_at_pixel", record_map_)
      .set_buffer<cl_uchar>("new_in_tile", new_in_tile_)
      .set_buffer<cl_float>("clamped_radius", radii_);
  clamp_.launch(count, gpu_.groups().per_record);
  apply_.set_buffer<CacheRecord>("records", records).set("params", params).set_buffer<cl_float>("clamped_radius", radii_);
  apply_.launch(count, gpu_.groups().per_item);
  gpu_.queue().finish();
}

std::vector<int32_t> PlacementPass::record_at_pixel() {
  return gpu_.download<int32_t>(record_map_, gbuffer_.pixel_count());
}

}  // namespace rcsplat
