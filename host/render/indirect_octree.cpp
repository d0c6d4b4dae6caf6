// The classic irradiance cache (Ward et al. 1988) on the host, the baseline the paper measured against: the same
// coarse-to-fine placement, records and neighbour clamping as the splat, but records computed with Embree on C++
// threads and every pixel interpolated by an octree lookup of the records whose weight exceeds 1/a.
#include <cmath>
#include <mutex>

#include "bvh/embree_scene.h"
#include "cache/cache_math.h"
#include "cache/host_records.h"
#include "cache/octree_lookup.h"
#include "render/indirect.h"
#include "util/log.h"
#include "util/parallel.h"

namespace rcsplat {

using glm::dvec3;
using glm::vec3;

void octree_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  check_cache_settings(cs);
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const int width = img.width, height = img.height;
  const size_t pixels = size_t(width) * size_t(height);
  CameraParams cam = f.gpu.download<CameraParams>(f.gbuffer.camera(), 1)[0];
  std::vector<GBufferSample> gb = f.gbuffer.download();
  std::vector<PixelGeometry> geo(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const GBufferSample& s = gb[i];
    geo[i] = {vec3(s.position[0], s.position[1], s.position[2]), vec3(s.normal[0], s.normal[1], s.normal[2]),
              vec3(s.geometric_normal[0], s.geometric_normal[1], s.geometric_normal[2]), s.triangle >= 0};
  }

  auto t = Clock::now();
  PackedScene packed = pack_scene(f.scene);
  EmbreeScene embree(f.scene.positions);
  HostShading shading(packed, embree);
  const float min_radius = hemisphere_params(cs, f.settings.seed, 1).min_spacing;  // in pixel footprints
  RecordOctree octree(dvec3(f.scene.bounds_min()), dvec3(f.scene.bounds_max()));
  std::vector<CacheRecord> records;
  std::vector<int32_t> record_at_pixel(pixels, -1);
  st.placement_s += seconds_since(t);

  int coarsest = coarsest_placement_spacing(cs);
  Progress progress("irradiance cache (octree)", size_t(std::log2(coarsest)) + 1);
  for (int spacing = coarsest, level = 0; spacing >= 1; spacing /= 2, ++level) {
    for (int round = 0; round < (spacing == 1 ? 4 : 1); ++round) {
      t = Clock::now();
      std::vector<uint32_t> candidates;
      for (int y = 0; y < height; y += spacing)
        for (int x = 0; x < width; x += spacing) {
          size_t i = size_t(y) * size_t(width) + size_t(x);
          if (geo[i].valid && record_at_pixel[i] < 0 && interpolate(octree, records, geo[i], cs.accuracy).weight == 0.0)
            candidates.push_back(uint32_t(i));
        }
      st.placement_s += seconds_since(t);
      if (candidates.empty()) break;

      t = Clock::now();
      size_t first = records.size();
      records.resize(first + candidates.size());
      std::vector<uint64_t> rays(candidates.size());
      parallel_for(candidates.size(), [&](size_t c) {
        const PixelGeometry& g = geo[candidates[c]];
        HostRecord r = compute_host_record(shading, g.p, g.n, g.ng, candidates[c], pixel_world_size(cam, g.p),
                                           hemisphere_params(cs, f.settings.seed, spacing));
        records[first + c] = to_cache_record(r);
        rays[c] = r.rays;
      }, 4);
      for (uint64_t r : rays) st.record_rays += r;
      st.records_s += seconds_since(t);

      // Neighbour clamping as the device does it: pairs with a new record, older records only in the first round.
      t = Clock::now();
      for (size_t k = first; k < records.size(); ++k) {
        record_at_pixel[size_t(records[k].pixel)] = int32_t(k);
        octree.insert(uint32_t(k), dvec3(record_position(records[k])), double(cs.accuracy) * records[k].radius);
      }
      std::vector<float> clamped(records.size());
      parallel_for(records.size(), [&](size_t i) {
        const CacheRecord& ri = records[i];
        clamped[i] = ri.radius;
        if (i < first && round > 0) return;
        vec3 pi = record_position(ri);
        octree.for_each_near(dvec3(pi), ri.radius, [&](uint32_t j) {
          if (j == i || (i < first && j < first)) return;
          if (glm::distance(pi, record_position(records[j])) >= ri.radius) return;
          clamped[i] = std::min(clamped[i], records[j].radius + glm::distance(pi, record_position(records[j])));
        });
        clamped[i] = std::max(clamped[i], std::min(ri.radius, min_radius * ri.pixel_size));
      });
      for (size_t i = 0; i < records.size(); ++i) records[i].radius = clamped[i];
      st.placement_s += seconds_since(t);
      count_placed(st, spacing, uint32_t(candidates.size()));
    }
    progress.update(size_t(level + 1));
  }
  progress.finish();

  t = Clock::now();
  img.indirect.assign(pixels * 3, 0.0f);
  img.irradiance.assign(pixels * 3, 0.0f);
  img.coverage.assign(pixels, 0.0f);
  img.records_per_pixel.assign(pixels, 0.0f);
  img.record_positions.assign(pixels, 0.0f);
  parallel_for(pixels, [&](size_t i) {
    if (!geo[i].valid) return;
    Interpolation in = interpolate(octree, records, geo[i], cs.accuracy);
    img.coverage[i] = float(in.weight);
    img.records_per_pixel[i] = float(in.count);
    if (in.weight == 0.0) return;
    dvec3 e = in.weighted / in.weight;
    for (int c = 0; c < 3; ++c) {
      img.irradiance[3 * i + size_t(c)] = float(e[c]);
      img.indirect[3 * i + size_t(c)] = float(img.albedo[3 * i + size_t(c)] / 3.14159265358979323846 * e[c]);
    }
  }, 256);
  st.resolve_s = seconds_since(t);
  for (size_t i = 0; i < pixels; ++i) {
    if (record_at_pixel[i] >= 0) img.record_positions[i] = 1.0f;
    if (geo[i].valid && img.coverage[i] == 0.0f) ++st.uncovered_pixels;
    for (size_t c = 0; c < 3; ++c) img.color[3 * i + c] += img.indirect[3 * i + c];
  }
  st.records = records.size();
  count_clamped_radii(records, cs, st);
  img.records = std::move(records);
}

}  // namespace rcsplat
