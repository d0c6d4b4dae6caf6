// Radiance cache splatting (Gautron et al. 2005) as the paper's algorithm box: place records coarse to fine where no
// record reaches, compute each level's records as one batch, clamp radii against neighbours, splat, and finally
// normalise and compose.
#include <algorithm>
#include <glm/glm.hpp>

#include "passes/record_pass.h"
#include "passes/splat_pass.h"
#include "render/device_record_index.h"
#include "render/indirect.h"
#include "render/placement.h"

namespace rcsplat {

RecordPass& frame_record_pass(IndirectFrame& f, const CacheSettings& cache, bool radiance) {
  const PhotonMapPass* photon_map = attach_photon_map(f);
  BuildTimer builds(f.gpu, f.image.stats.program_s);
  // Radiance records keep the caustic paths in their rays: the map's irradiance reaches only the diffuse base and rough
  // lobes (kernels/caustic_map.cl).
  const bool caustics_apart = !radiance && f.plan.passes.caustic_map;
  if (caustics_apart) attach_caustic_map(f);
  const MethodPasses::RecordKey key{largest_theta_strata(cache), photon_map != nullptr, caustics_apart};
  RecordPass& records = (radiance ? f.passes.radiance_records : f.passes.irradiance_records).get(key, [&] {
    return std::make_unique<RecordPass>(f.gpu, f.device_scene, key.theta_strata, radiance, key.photon_gather,
                                        key.caustics_apart);
  });
  builds.stop();
  records.begin_frame(photon_map, f.settings.bounces);
  attach_light_guide(f, records);
  return records;
}

namespace {

// The G-buffer pixels (of `camera`, device coordinates) the records' positions project to, each once: where a record a
// move marked is computed again.
std::vector<cl_uint> pixels_seeing(const CameraParams& camera, const std::vector<CacheRecord>& records) {
  std::vector<cl_uint> pixels;
  const glm::vec3 eye(camera.eye[0], camera.eye[1], camera.eye[2]), right(camera.right[0], camera.right[1], camera.right[2]),
      up(camera.up[0], camera.up[1], camera.up[2]), forward(camera.forward[0], camera.forward[1], camera.forward[2]);
  for (const CacheRecord& r : records) {
    const glm::vec3 d = glm::vec3(r.position[0], r.position[1], r.position[2]) - eye;
    const float z = glm::dot(d, forward);
    float sx, sy;
    if (camera.orthographic) {
      sx = glm::dot(d, right) / (camera.half_height * camera.aspect);
      sy = glm::dot(d, up) / camera.half_height;
    } else {
      if (!(z > 0.0f)) continue;
      sx = glm::dot(d, right) / (z * camera.tan_half_fov_y * camera.aspect);
      sy = glm::dot(d, up) / (z * camera.tan_half_fov_y);
    }
    const float x = 0.5f * (sx + 1.0f) * float(camera.width), y = 0.5f * (1.0f - sy) * float(camera.height);
    if (!(x >= 0.0f && x < float(camera.width) && y >= 0.0f && y < float(camera.height))) continue;
    pixels.push_back(cl_uint(int(y) * camera.width + int(x)));
  }
  std::sort(pixels.begin(), pixels.end());
  pixels.erase(std::unique(pixels.begin(), pixels.end()), pixels.end());
  return pixels;
}

}  // namespace

void splat_indirect(IndirectFrame& f) {
  const CacheSettings& cs = f.settings.cache;
  RenderedImage& img = f.image;
  RenderStats& st = img.stats;
  const GBufferView& gbuffer = f.gbuffer.view();
  // Kept records computed with other settings go, and the photons kept with them (the maps are made again).
  if (f.kept_records && f.kept_records->begin_frame(kept_records_key(f.settings))) *f.kept_light = KeptLight{};
  RecordPass& records = frame_record_pass(f, cs, false);
  BuildTimer builds(f.gpu, st.program_s);
  DeviceRecordIndex& index =
      f.passes.irradiance_index.get({}, [&] { return std::make_unique<DeviceRecordIndex>(f.gpu, gbuffer, cs); });
  index.begin(gbuffer, cs);
  SplatPass& splat = f.passes.splat.get({}, [&] { return std::make_unique<SplatPass>(f.gpu); });
  builds.stop();

  // Records kept from earlier frames (a walkthrough): those this view may see, fitted to it and seated first. Those a
  // move marked (scene/scene_animator.h, KeptRecords::mark_moved) are computed again where they stand, seen from the
  // pixel they project to, before placement: the cache keeps its layout, so a move changes the light and not where
  // the records are (placing them anew moved their pattern from frame to frame: flicker).
  uint32_t kept = 0, recomputed = 0;
  f.passes.in_place = {};
  if (f.kept_records) {
    std::vector<CacheRecord> moved;
    {
      StageTimer timing(st.irradiance.placement_s);
      const std::vector<CacheRecord> reused = f.kept_records->for_view(*f.camera, cs, nullptr, &moved);
      kept = uint32_t(reused.size());
      records.load(reused);
      index.seat_kept(records, kept, cs);
    }
    const std::vector<cl_uint> pixels = pixels_seeing(*f.camera, moved);
    if (!pixels.empty()) {
      recomputed = uint32_t(pixels.size());
      const cl::Buffer candidates = f.gpu.upload(pixels, CL_MEM_READ_ONLY, "records");
      f.passes.in_place = {&records, pixels, kept, hemisphere_params(cs, f.settings.seed, coarsest_placement_spacing(cs))};
      {
        StageTimer timing(st.irradiance.records_s);
        records.compute(gbuffer, candidates, recomputed, kept, f.passes.in_place.hemisphere);
      }
      StageTimer timing(st.irradiance.placement_s);
      index.add_records(records, kept, recomputed);
      index.clamp_neighbours(records, kept + recomputed, kept, true);
    }
  }
  uint32_t total = place_records(index, records, gbuffer, cs, f.settings.seed, st.irradiance, {}, "irradiance cache",
                                 kept + recomputed);
  {
    // One splat of every record with its final radius, at the frame's fixed-point scale.
    StageTimer timing(st.irradiance.splat_s);
    splat.splat_all(gbuffer, records.records(), total, cs.accuracy);
  }
  {
    StageTimer timing(st.irradiance.resolve_s);
    splat.resolve(gbuffer);
    if (cs.finest_spacing_pixels > 1)  // sub-pixels: placement stopped one output pixel apart
      st.irradiance.filled_sub_pixels = splat.fill_uncovered(gbuffer, records.records(), index.record_at_pixel_buffer(),
                                                  int(std::ceil(cs.max_reach_pixels)));
  }
  {
    StageTimer timing(st.primary.layers_s);
    // The records stay on the device: a frame with every layer brings them back (tests read them); a colour-only
    // frame counts its clamped reaches there and brings back only those a walkthrough keeps.
    if (!layers_stay_on_device(f.settings)) {
      img.records = records.download(0, total);
      count_clamped_radii(img.records, cs, st.irradiance);
      if (f.kept_records) f.kept_records->add(img.records.data() + kept, total - kept, nullptr, 0, recomputed);
    } else {
      const std::array<uint64_t, 2> clamped = f.layers.count_clamped_reaches(records.records(), total, cs);
      st.irradiance.at_min_radius += clamped[0];
      st.irradiance.at_max_radius += clamped[1];
      if (f.kept_records) {
        const std::vector<CacheRecord> added = records.download(kept, total - kept);
        f.kept_records->add(added.data(), added.size(), nullptr, 0, recomputed);
      }
    }
    if (f.kept_records) st.kept_records = f.kept_records->stats();
  }
  const RadianceSplatPass* radiance = radiance_cached_lobes(f);
  compose_cached_indirect(f, splat.irradiance(), radiance, &records.records(), total);
  fill_cache_layers(f, splat.irradiance(), splat.records_per_pixel_buffer(), index.record_at_pixel_buffer());
}

}  // namespace rcsplat
