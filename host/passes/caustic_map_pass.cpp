#include "passes/caustic_map_pass.h"

#include <algorithm>
#include <cmath>

#include "kernels/photon_grid.h"
#include "passes/light_guide_pass.h"

namespace rcsplat {
void CausticMapPass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }
namespace {

// Photons the radius is fitted on (every k-th, so the same photons give the same radius) and the fixed-point steps.
constexpr size_t kRadiusSample = 4096;
constexpr int kRadiusSteps = 4;

}  // namespace

size_t photon_neighbour_count(const PhotonGrid& grid, const PhotonHit& p, size_t enough) {
  const PhotonMapParams& g = grid.params;
  const float r2 = g.radius * g.radius;
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = photon_cell(p.position[a], g.grid_origin[a], g.cell_size);
  uint32_t visited[27];
  size_t visited_count = 0, count = 0;
  for (int k = 0; k < 27; ++k) {
    uint32_t bucket = photon_bucket(c[0] + k % 3 - 1, c[1] + (k / 3) % 3 - 1, c[2] + k / 9 - 1, g.bucket_count);
    if (std::find(visited, visited + visited_count, bucket) != visited + visited_count) continue;
    visited[visited_count++] = bucket;
    for (uint32_t j = grid.bucket_starts[bucket]; j < grid.bucket_starts[bucket + 1]; ++j) {
      const PhotonHit& q = grid.photons[j];
      float d2 = 0.0f, facing = 0.0f;
      for (int a = 0; a < 3; ++a) {
        float d = q.position[a] - p.position[a];
        d2 += d * d;
        facing += q.normal[a] * p.normal[a];
      }
      count += d2 < r2 && facing > PHOTON_MIN_NORMAL_COSINE;
    }
    if (count > enough) break;  // p itself is among them
  }
  return count > 0 ? count - 1 : 0;
}

std::vector<PhotonHit> shoot_caustic_photons(GpuContext& gpu, const DeviceScene& scene, unsigned paths, unsigned seed) {
  return lit_landings(LightGuidePass(gpu, scene).shoot(paths, seed, 2, 1, PhotonKeep::after_sharp_lobe));
}

float crowded_gather_radius(const std::vector<PhotonHit>& photons, float start, unsigned neighbours) {
  if (photons.empty() || !(start > 0.0f) || !std::isfinite(start)) return start;
  const size_t stride = std::max<size_t>(photons.size() / kRadiusSample, 1);
  float radius = start;
  for (int step = 0; step < kRadiusSteps; ++step) {
    const PhotonGrid grid = sort_into_grid(photons, radius);
    double found = 0.0;
    size_t sampled = 0;
    for (size_t i = 0; i < photons.size(); i += stride, ++sampled) found += double(photon_neighbour_count(grid, photons[i]));
    const double mean = found / double(sampled);
    // The count grows as r^2 on a surface: one step of that model, damped to a factor of 4 each way.
    const double scale = std::clamp(std::sqrt(double(neighbours) / std::max(mean, 0.25)), 0.25, 4.0);
    radius = std::min(start, float(radius * scale));
  }
  return radius;
}

CausticMapPass::CausticMapPass(GpuContext& gpu, const std::vector<PhotonHit>& photons, float radius)
    : gpu_(gpu),
      add_(gpu.kernel(kProgram, "add_caustics", {})),
      add_to_records_(gpu.kernel(kProgram, "add_caustics_to_records", {})) {
  const PhotonGrid grid = sort_into_grid(photons, radius);
  params_ = grid.params;
  // A kernel reads no photon of an empty map, but buffers must be bound.
  photons_ = gpu.upload(grid.photons.empty() ? std::vector<PhotonHit>(1) : grid.photons, CL_MEM_READ_ONLY,
                        "caustic map");
  buckets_ = gpu.upload(grid.bucket_starts.empty() ? std::vector<cl_uint>(2, 0u) : grid.bucket_starts,
                        CL_MEM_READ_ONLY, "caustic map buckets");
}

void CausticMapPass::add_to(const GBufferView& gbuffer, const cl::Buffer& irradiance) {
  if (params_.photon_count == 0) return;
  gbuffer.bind(add_);
  bind(add_);
  add_.set_buffer<cl_float4>("irradiance", irradiance);
  add_.launch(gbuffer.pixel_count(), gpu_.groups().traversal);
  gpu_.queue().finish();
}

void CausticMapPass::bind(NamedKernel& kernel) const {
  kernel.set_buffer<PhotonHit>("caustic_photons", photons_)
      .set_buffer<cl_uint>("caustic_buckets", buckets_)
      .set("caustic_grid", params_);
}

const cl::Buffer& CausticMapPass::lit_records(const cl::Buffer& records, uint32_t record_count) {
  if (params_.photon_count == 0 || record_count == 0) return records;
  gpu_.reserve<CacheRecord>(lit_records_, lit_capacity_, record_count, "caustic map: lit records");
  bind(add_to_records_);
  add_to_records_.set_buffer<CacheRecord>("records", records)
      .set("record_count", cl_uint(record_count))
      .set_buffer<CacheRecord>("lit", lit_records_);
  add_to_records_.launch(record_count, gpu_.groups().per_item);
  return lit_records_;
}

}  // namespace rcsplat
