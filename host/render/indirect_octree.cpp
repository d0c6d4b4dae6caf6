// The classic irradiance cache (Ward et al. 1988), the baseline the paper measured against: the same coarse-to-fine
// placement and the same records as the splat (render/placement.h), but coverage, neighbour clamping and every
// pixel's interpolation go through a loose octree of the records on the host, on C++ threads.
#include <atomic>
#include <cfloat>
#include <cmath>
#include <numbers>

#include "cache/octree_lookup.h"
#include "render/indirect.h"
#include "render/placement.h"
#include "util/parallel.h"

namespace rcsplat {
namespace {

using glm::dvec3;
using glm::vec3;

// Placement's coverage and clamping on the host, through the octree. Keeps its own copy of the records, whose radii
// it clamps.
class OctreeRecordIndex final : public RecordIndex {
 public:
  OctreeRecordIndex(GpuContext& gpu, std::vector<PixelGeometry> pixels, int width, int height, const Scene& scene,
                    const SceneFrame& frame, const CacheSettings& cache)
      : gpu_(gpu),
        pixels_(std::move(pixels)),
        width_(width),
        height_(height),
        accuracy_(cache.accuracy),
        min_radius_pixels_(min_radius_pixels(cache)),
        octree_(dvec3(frame.to_device(scene.bounds_min())), dvec3(frame.to_device(scene.bounds_max()))),
        record_at_pixel_(pixels_.size(), -1),
        candidates_(
            gpu.buffer(CL_MEM_READ_ONLY, std::max<size_t>(pixels_.size(), 1) * sizeof(cl_uint), "octree candidates")) {}

  uint32_t find_uncovered(RecordPass&, uint32_t, int spacing, uint32_t) override {
    std::vector<cl_uint> found;
    for (int y = 0; y < height_; y += spacing)
      for (int x = 0; x < width_; x += spacing) {
        size_t i = size_t(y) * size_t(width_) + size_t(x);
        if (pixels_[i].valid && record_at_pixel_[i] < 0 && !covered(octree_, records_, pixels_[i], accuracy_))
          found.push_back(cl_uint(i));
      }
    if (!found.empty())
      gpu_.queue().enqueueWriteBuffer(candidates_, CL_TRUE, 0, found.size() * sizeof(cl_uint), found.data());
    return uint32_t(found.size());
  }
  const cl::Buffer& candidates() const override { return candidates_; }

  void add_records(RecordPass& records, uint32_t first, uint32_t count) override {
    std::vector<CacheRecord> batch = records.download(first, count);
    records_.insert(records_.end(), batch.begin(), batch.end());
    for (size_t k = first; k < records_.size(); ++k) {
      record_at_pixel_[size_t(records_[k].pixel)] = int32_t(k);
      octree_.insert(uint32_t(k), dvec3(record_position(records_[k])), double(accuracy_) * records_[k].radius);
    }
  }

  void clamp_neighbours(RecordPass&, uint32_t count, uint32_t first_new, bool clamp_older) override {
    std::vector<float> clamped(count);
    parallel_for(count, [&](size_t i) {
      const CacheRecord& ri = records_[i];
      clamped[i] = ri.radius;
      if (i < first_new && !clamp_older) return;
      vec3 pi = record_position(ri);
      float smallest = ri.radius;
      octree_.for_each_near(dvec3(pi), ri.radius, [&](uint32_t j) {
        if (j == i || (i < first_new && j < first_new)) return;  // an old record only pairs with new ones
        smallest = rc_fmin(smallest, neighbour_radius_bound(pi, record_position(records_[j]), records_[j].radius));
      });
      clamped[i] = neighbour_clamped_radius(ri.radius, smallest, min_radius_pixels_, ri.pixel_size);
    });
    for (size_t i = 0; i < count; ++i) records_[i].radius = clamped[i];
  }

  const RecordOctree& octree() const { return octree_; }
  const std::vector<int32_t>& record_at_pixel() const { return record_at_pixel_; }
  std::vector<CacheRecord>& records() { return records_; }

 private:
  GpuContext& gpu_;
  std::vector<PixelGeometry> pixels_;
  int width_, height_;
  float accuracy_, min_radius_pixels_;
  RecordOctree octree_;
  std::vector<CacheRecord> records_;
  std::vector<int32_t> record_at_pixel_;
  cl::Buffer candidates_;
};

}  // namespace

void octree_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const GBufferView& view = f.gbuffer.view();  // the sub-pixels' frame, where records are placed and interpolated
  const size_t pixels = view.pixel_count();
  std::vector<GBufferSample> gb = f.gbuffer.download();
  std::vector<PixelGeometry> geo(pixels);
  for (size_t i = 0; i < pixels; ++i) geo[i] = pixel_geometry(gb[i]);

  RecordPass& records = frame_record_pass(f, cs, false);
  OctreeRecordIndex index(f.gpu, geo, view.width, view.height, f.scene, f.device_scene.frame(), cs);
  place_records(index, records, view, cs, f.settings.seed, st.irradiance);

  StageTimer timing(st.irradiance.resolve_s);
  // The sub-pixels' interpolated irradiance (E, weight) and records reaching each, which the device composes and
  // gathers into the image's layers as the splat's.
  std::vector<cl_float4> irradiance(pixels, cl_float4{{0, 0, 0, 0}});
  std::vector<cl_uint> reaching(pixels, 0);
  // With sub-pixels, placement stops one output pixel apart: a sub-pixel no record reaches (a sliver along an edge)
  // takes the splat's choice of a record near it (record_for_uncovered_pixel), so records stay one sample's.
  const bool fill = cs.finest_spacing_pixels > 1;
  const int window = int(std::ceil(cs.max_reach_pixels));
  std::atomic<uint32_t> filled{0};
  parallel_for(pixels, [&](size_t i) {
    if (!geo[i].valid) return;
    Interpolation in = interpolate(index.octree(), index.records(), geo[i], cs.accuracy);
    reaching[i] = cl_uint(in.count);
    if (in.weight == 0.0 && fill) {
      float w = 0.0f;
      int k = record_for_uncovered_pixel(index.records().data(), index.record_at_pixel().data(), view.width,
                                         view.height, int(i % size_t(view.width)), int(i / size_t(view.width)), window,
                                         geo[i].p, geo[i].n, &w);
      if (k >= 0) {
        in.weight = std::fmax(w, FLT_MIN);
        in.weighted = in.weight * dvec3(record_irradiance(index.records()[size_t(k)]));
        ++filled;
      }
    }
    if (in.weight == 0.0) return;
    dvec3 e = in.weighted / in.weight;
    for (int c = 0; c < 3; ++c) irradiance[i].s[c] = float(e[c]);
    irradiance[i].s[3] = float(in.weight);
  }, 256);
  timing.stop();
  st.irradiance.filled_sub_pixels = filled;
  const cl::Buffer irradiance_buffer = f.gpu.upload(irradiance, CL_MEM_READ_WRITE, "octree irradiance");
  // The octree's records, where the glossy pass may read them: its grid of them is built on the device.
  const std::vector<CacheRecord>& octree_records = index.records();
  cl::Buffer records_buffer;
  if (f.plan.passes.world_record_grid)
    records_buffer = f.gpu.upload(octree_records.empty() ? std::vector<CacheRecord>(1) : octree_records,
                                  CL_MEM_READ_ONLY, "octree records");
  compose_cached_indirect(f, irradiance_buffer, nullptr, records_buffer() ? &records_buffer : nullptr,
                          uint32_t(octree_records.size()));
  fill_cache_layers(f, irradiance_buffer, f.gpu.upload(reaching, CL_MEM_READ_ONLY, "octree records per pixel"),
                    f.gpu.upload(index.record_at_pixel(), CL_MEM_READ_ONLY, "octree record map"));
  img.records = std::move(index.records());
  count_clamped_radii(img.records, cs, st.irradiance);
}

}  // namespace rcsplat
