// Cache files (issue 42, item 3; sequence/cache_file.h): records round-trip bit for bit, a process that reads the file
// renders the next frame as the writer would have, and every bad file is refused by name before any frame.
#include "sequence/cache_file.h"

#include <gtest/gtest.h>

#include <map>

#include <random>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "sequence/walkthrough.h"
#include "image/image_io.h"
#include "sequence/cache_merge.h"
#include "render/renderer.h"
#include "cache/octree_lookup.h"
#include "scene/cornell_box.h"
#include "lobed_cornell_box.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// FNV-1a, 64 bits, written again here: a patched file gets a valid checksum, so the check after it is what refuses.
void reseal(std::string& bytes) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 0; i + 8 < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
  std::memcpy(bytes.data() + bytes.size() - 8, &h, 8);
}

WalkthroughRequest orbit(const fs::path& dir) {
  WalkthroughRequest o;
  o.render.settings = test::one_bounce_one_sample();
  o.render.settings.width = o.render.settings.height = 40;
  o.render.settings.light_samples = 4;
  o.orbit_seconds = 4.0;
  o.orbit_degrees = 40.0;
  o.fps = 2.0;
  o.render.outputs = {(dir / "f%d.exr").string()};
  return o;
}

// The lobed Cornell box (a glossy floor that casts caustics, a radiance-cached box) with two bounces from the photon map
// and the light guide: every part of a cache file is written.
RenderSettings everything_kept() {
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = 40;
  s.light_samples = 4;
  s.bounces = 2;
  s.bounce_method = BounceMethod::photons;
  s.photon_paths = 1u << 14;
  s.caustic_photons = 1u << 14;
  s.keep_records = true;
  return s;
}

RenderSettings at_pose(const Scene& scene, int pose) {
  RenderSettings s = everything_kept();
  const SceneCamera& camera = scene.cameras[0];
  s.camera_overrides.eye =
      camera.eye + 0.05f * float(pose) * glm::normalize(glm::cross(camera.target - camera.eye, camera.up));
  s.camera_overrides.target = camera.target;
  return s;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(CacheFile, EverythingKeptRoundTripsBitForBit) {
  const Scene scene = test::cornell_box_with_lobes(0.1f, 0.5f);
  Renderer renderer(test::gpu(), scene);
  const FramePlan plan = renderer.plan(at_pose(scene, 0));
  renderer.render(plan);
  renderer.render(renderer.plan(at_pose(scene, 1)));
  const KeptCache& kept = renderer.kept_records();
  ASSERT_GT(kept.irradiance.size(), 100u);
  ASSERT_GT(kept.radiance.size(), 20u);
  ASSERT_GT(kept.radiance.payload_per_record(), 0u);
  ASSERT_TRUE(kept.light.has_photon_map && kept.light.has_caustic_map && kept.light.has_guide);
  ASSERT_FALSE(kept.light.photons.empty() || kept.light.caustic_photons.empty() || kept.light.guide_clusters.empty());
  const KeptRecordsKey key = kept_records_key(plan.frame_settings());
  const CacheFileIdentity identity{scene_fingerprint(scene), settings_fingerprint(key), "test"};
  const std::string path = test::scratch_dir() + "/lobed.cache";
  renderer.kept_records().times = RecordTimes{3, false, 24.0, 1.25};  // as a moving scene's walkthrough would end
  write_cache_file(path, kept, identity);
  KeptCache read(1u << 20);
  read_cache_file(path, identity, key, cache_file_limits(plan.frame_settings()), read);
  EXPECT_EQ(read.times, kept.times);
  for (const auto& [a, b] : {std::pair{&read.irradiance, &kept.irradiance}, std::pair{&read.radiance, &kept.radiance}}) {
    EXPECT_TRUE(same_bytes(a->records(), b->records()));
    EXPECT_EQ(a->last_used(), b->last_used());
    EXPECT_TRUE(same_bytes(a->payload(), b->payload()));
    EXPECT_EQ(a->frames_begun(), b->frames_begun());
  }
  EXPECT_EQ(read.radiance.largest_radiance(), kept.radiance.largest_radiance());
  EXPECT_TRUE(same_bytes(read.light.photons, kept.light.photons));
  EXPECT_TRUE(same_bytes(read.light.caustic_photons, kept.light.caustic_photons));
  EXPECT_TRUE(same_bytes(read.light.guide_clusters, kept.light.guide_clusters));
  EXPECT_EQ(read.light.photon_paths, kept.light.photon_paths);
  EXPECT_EQ(read.light.guide_hits, kept.light.guide_hits);
  const size_t records = kept.irradiance.size() + kept.radiance.size();
  EXPECT_EQ(read_bytes(path).size(), 168 + 8 + 16 + records * 168 + kept.radiance.payload().size() * 4 + 20 +
                                         kept.light.photons.size() * 64 + 12 + kept.light.caustic_photons.size() * 64 +
                                         20 + kept.light.guide_clusters.size() * 48 + 8);
}

// A Renderer whose maps and guide were built by a frame that kept nothing shoots them again (the same photons) for its
// first frame that keeps records, so that a cache file written after it holds them, and renders what a Renderer that
// kept from the start renders.
TEST(CacheFile, MapsBuiltBeforeAnyRecordWasKeptAreKeptWithTheRecords) {
  const Scene scene = test::cornell_box_with_lobes(0.1f, 0.5f);
  Renderer renderer(test::gpu(), scene);
  RenderSettings first = at_pose(scene, 0);
  first.keep_records = false;
  renderer.render(renderer.plan(first));
  const RenderedImage keeping = renderer.render(renderer.plan(at_pose(scene, 0)));
  const KeptLight& light = renderer.kept_records().light;
  EXPECT_TRUE(light.has_photon_map && !light.photons.empty());
  EXPECT_TRUE(light.has_caustic_map && !light.caustic_photons.empty());
  EXPECT_TRUE(light.has_guide && !light.guide_clusters.empty());
  Renderer from_the_start(test::gpu(), scene);
  EXPECT_EQ(keeping.color, from_the_start.render(from_the_start.plan(at_pose(scene, 0))).color);
  EXPECT_TRUE(same_bytes(light.photons, from_the_start.kept_records().light.photons));
}

// A process that reads the file renders the writer's next frame, bit for bit, with the writer's photons: the same file
// with every photon map photon's power doubled gives another frame (so the photons are read, not shot again).
TEST(CacheFile, AFrameFromAFileIsTheWritersNextFrameWithTheFilesLight) {
  const Scene scene = test::cornell_box_with_lobes(0.1f, 0.5f);
  Renderer writer(test::gpu(), scene);
  writer.render(writer.plan(at_pose(scene, 0)));
  writer.render(writer.plan(at_pose(scene, 1)));
  const FramePlan next = writer.plan(at_pose(scene, 2));
  const KeptRecordsKey key = kept_records_key(next.frame_settings());
  const CacheFileIdentity identity{scene_fingerprint(scene), settings_fingerprint(key), "test"};
  const std::string path = test::scratch_dir() + "/walk.cache";
  write_cache_file(path, writer.kept_records(), identity);
  const KeptCache& kept = writer.kept_records();
  const size_t photons_at = 168 + 8 + kept.irradiance.size() * 168 + 16 + kept.radiance.size() * 168 +
                            kept.radiance.payload().size() * 4 + 4 + 8 + 8;
  const size_t photons = kept.light.photons.size();
  const RenderedImage expected = writer.render(next);

  Renderer reader(test::gpu(), scene);
  read_cache_file(path, identity, key, cache_file_limits(next.frame_settings()), reader.kept_records());
  const RenderedImage frame = reader.render(reader.plan(at_pose(scene, 2)));
  EXPECT_EQ(frame.color, expected.color);
  EXPECT_EQ(frame.stats.photon_map.shoot_s, 0.0) << "photons shot again";

  std::string bytes = read_bytes(path);
  for (size_t i = 0; i < photons; ++i)
    for (size_t field : {32u, 48u})  // flux and incident
      for (size_t c = 0; c < 3; ++c) {
        float v;
        std::memcpy(&v, bytes.data() + photons_at + 64 * i + field + 4 * c, 4);
        v *= 2.0f;
        std::memcpy(bytes.data() + photons_at + 64 * i + field + 4 * c, &v, 4);
      }
  reseal(bytes);
  test::write_file(path, bytes);
  Renderer brighter(test::gpu(), scene);
  read_cache_file(path, identity, key, cache_file_limits(next.frame_settings()), brighter.kept_records());
  EXPECT_NE(brighter.render(brighter.plan(at_pose(scene, 2))).color, expected.color);
}

// A walk rendered in one process, and the same walk split at frame 2 into two processes joined by a cache file: the
// frames after the split are the same bits.
TEST(CacheFile, ARenderFromALoadedCacheIsTheWritersNextFrame) {
  const fs::path dir = test::scratch_dir();
  WalkthroughRequest whole = orbit(dir / "whole");
  fs::create_directories(dir / "whole");
  whole.last_frame = 3;
  ASSERT_NO_THROW(render_walkthrough(whole));
  fs::create_directories(dir / "split");
  WalkthroughRequest before = orbit(dir / "split");
  before.last_frame = 2;
  before.render.cache_out = (dir / "walk.cache").string();
  ASSERT_NO_THROW(render_walkthrough(before));
  WalkthroughRequest after = orbit(dir / "split");
  after.first_frame = after.last_frame = 3;
  after.render.cache_in = before.render.cache_out;
  ASSERT_NO_THROW(render_walkthrough(after));
  int w = 0, h = 0;
  for (const char* f : {"f2.exr", "f3.exr"})
    EXPECT_EQ(read_exr_rgb((dir / "whole" / f).string(), w, h), read_exr_rgb((dir / "split" / f).string(), w, h)) << f;
  // Without the file, frame 3 alone is a fresh cache's: other bits.
  WalkthroughRequest alone = orbit(dir / "alone");
  fs::create_directories(dir / "alone");
  alone.first_frame = alone.last_frame = 3;
  ASSERT_NO_THROW(render_walkthrough(alone));
  EXPECT_NE(read_exr_rgb((dir / "alone/f3.exr").string(), w, h), read_exr_rgb((dir / "whole/f3.exr").string(), w, h));
}

// A fixed cache (--cache-fixed): every frame starts from the file's records alone, so a frame is the same bits whatever
// range of frames a process renders (a walkthrough split over tasks). Frame 3 from a run of frames 1 to 3 and from a
// run of frame 3 alone; the run's frame 1 from a run of frames 0 to 1. Without --cache-fixed the longer run's frame 3
// would have read the records frames 1 and 2 placed.
TEST(CacheFile, AFixedCacheRendersAFrameTheSameWhateverRangeRendersIt) {
  const fs::path dir = test::scratch_dir();
  WalkthroughRequest writer = orbit(dir / "unused");
  writer.render.outputs.clear();
  writer.render.outputs = {(dir / "w%d.exr").string()};
  writer.last_frame = 0;
  writer.render.cache_out = (dir / "key.cache").string();
  ASSERT_NO_THROW(render_walkthrough(writer));
  auto fixed_run = [&](const std::string& name, long long first, long long last) {
    fs::create_directories(dir / name);
    WalkthroughRequest o = orbit(dir / name);
    o.first_frame = first;
    o.last_frame = last;
    o.render.cache_in = writer.render.cache_out;
    o.cache = CacheMode::fixed;
    EXPECT_NO_THROW(render_walkthrough(o));
  };
  fixed_run("long", 1, 3);
  fixed_run("short", 3, 3);
  fixed_run("first", 0, 1);
  int w = 0, h = 0;
  auto frame = [&](const std::string& name, int f) {
    return read_exr_rgb((dir / name / ("f" + std::to_string(f) + ".exr")).string(), w, h);
  };
  EXPECT_EQ(frame("long", 3), frame("short", 3));
  EXPECT_EQ(frame("long", 1), frame("first", 1));
  EXPECT_NE(frame("long", 1), frame("long", 3));
  // --cache-fixed reads a file and writes none.
  WalkthroughRequest bad = orbit(dir / "bad");
  bad.cache = CacheMode::fixed;
  EXPECT_THROW(render_walkthrough(bad), Error);
  bad.render.cache_in = writer.render.cache_out;
  bad.render.cache_out = (dir / "again.cache").string();
  EXPECT_THROW(render_walkthrough(bad), Error);
}

// A rerun of a stopped task (--skip-existing): only the frames whose files are missing are rendered, the same bits as
// the whole run's; the frames that are there are left as they are. Refused where frames depend on earlier ones.
TEST(CacheFile, ARerunWithSkipExistingRendersOnlyTheMissingFrames) {
  const fs::path dir = test::scratch_dir();
  WalkthroughRequest writer = orbit(dir);
  writer.render.outputs = {(dir / "w%d.exr").string()};
  writer.last_frame = 0;
  writer.render.cache_out = (dir / "key.cache").string();
  ASSERT_NO_THROW(render_walkthrough(writer));
  fs::create_directories(dir / "run");
  WalkthroughRequest run = orbit(dir / "run");
  run.last_frame = 3;
  run.render.cache_in = writer.render.cache_out;
  run.cache = CacheMode::fixed;
  ASSERT_NO_THROW(render_walkthrough(run));
  int w = 0, h = 0;
  const std::string f1 = (dir / "run/f1.exr").string(), f2 = (dir / "run/f2.exr").string();
  const std::vector<float> whole_f2 = read_exr_rgb(f2, w, h);
  const auto f1_written = fs::last_write_time(f1);
  fs::remove(f2);
  run.skip_existing = true;
  const WalkthroughResult rerun = render_walkthrough(run);
  EXPECT_EQ(read_exr_rgb(f2, w, h), whole_f2);
  EXPECT_EQ(fs::last_write_time(f1), f1_written);
  EXPECT_EQ(rerun.skipped, 3);
  EXPECT_EQ(rerun.rows.size(), 1u);
  WalkthroughRequest kept = run;  // each frame reading the records of the frames before it
  kept.cache = CacheMode::kept;
  kept.render.cache_in.clear();
  EXPECT_THROW(render_walkthrough(kept), Error);
}

// A cache pre-pass split over tasks (--cache-every, --cache-merge): two tasks' parts, merged in either order, are the
// same file as one task's part merged, and a frame rendered from it by a task of a few frames is the same bits as the
// frame of a run over every frame. Overlapping parts and a pre-pass without a file to write are refused.
TEST(CacheFile, APrePassSplitOverTasksMergesToTheSameCacheWhateverTheSplit) {
  const fs::path dir = test::scratch_dir();
  auto pre_pass = [&](const std::string& part, long long first, long long last) {
    WalkthroughRequest o = orbit(dir);
    o.render.outputs.clear();
    o.cache = CacheMode::pre_pass;
    o.cache_every = 3;
    o.first_frame = first;
    o.last_frame = last;
    o.render.cache_out = (dir / part).string();
    EXPECT_NO_THROW(render_walkthrough(o));
    return o.render.cache_out;
  };
  std::map<std::string, CacheMergeStats> merged;
  auto merge = [&](const std::vector<std::string>& parts, const std::string& out) {
    WalkthroughRequest o = orbit(dir);
    o.render.outputs.clear();
    o.cache = CacheMode::merge;
    o.cache_merge = parts;
    o.render.cache_out = (dir / out).string();
    EXPECT_NO_THROW(merged[out] = render_walkthrough(o).merge);
    return o.render.cache_out;
  };
  const std::string whole = pre_pass("whole.part", 0, 8);
  const std::string early = pre_pass("early.part", 0, 4), late = pre_pass("late.part", 5, 8);
  const std::string one = merge({whole}, "one.cache"), two = merge({late, early}, "two.cache");
  EXPECT_EQ(read_bytes(one), read_bytes(two));
  // Key frames 0, 3 and 6 overlap: the merge keeps fewer records than the parts hold.
  EXPECT_EQ(merged["one.cache"].key_frames, 3u);
  EXPECT_LT(merged["one.cache"].irradiance_kept, merged["one.cache"].irradiance_in);
  auto frames = [&](const std::string& name, const std::string& cache, long long first, long long last) {
    fs::create_directories(dir / name);
    WalkthroughRequest o = orbit(dir / name);
    o.first_frame = first;
    o.last_frame = last;
    o.render.cache_in = cache;
    o.cache = CacheMode::fixed;
    EXPECT_NO_THROW(render_walkthrough(o));
  };
  frames("all", one, 0, 8);
  frames("task", two, 4, 5);
  int w = 0, h = 0;
  for (int f : {4, 5})
    EXPECT_EQ(read_exr_rgb((dir / "all" / ("f" + std::to_string(f) + ".exr")).string(), w, h),
              read_exr_rgb((dir / "task" / ("f" + std::to_string(f) + ".exr")).string(), w, h))
        << "frame " << f;
  // Refused, with no file written: parts that share a key frame, a pre-pass without --cache-out or with a range
  // holding no key frame, a merge asked for images.
  const std::string overlap = pre_pass("overlap.part", 3, 5);
  WalkthroughRequest bad = orbit(dir);
  bad.render.outputs.clear();
  bad.cache = CacheMode::merge;
  bad.cache_merge = {early, overlap};
  bad.render.cache_out = (dir / "bad.cache").string();
  EXPECT_THROW(render_walkthrough(bad), Error);
  bad.cache = CacheMode::merge;
  bad.cache_merge = {early};
  bad.render.outputs = {(dir / "bad%d.exr").string()};
  EXPECT_THROW(render_walkthrough(bad), Error);
  bad = orbit(dir);
  bad.render.outputs.clear();
  bad.cache = CacheMode::pre_pass;
  bad.cache_every = 3;
  EXPECT_THROW(render_walkthrough(bad), Error);
  bad.render.cache_out = (dir / "bad.cache").string();
  bad.first_frame = 4;
  bad.last_frame = 5;
  EXPECT_THROW(render_walkthrough(bad), Error);
  EXPECT_FALSE(fs::exists(dir / "bad.cache"));
}

// The merge's thinning through its grid against every pair: a record is dropped exactly where a kept record of an
// earlier key frame reaches it (random records near a plane over two decades of radii, random horizons and normals).
TEST(CacheFile, TheMergeDropsExactlyTheRecordsAnEarlierKeyFrameReaches) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const size_t n = 3000;
  std::vector<CacheRecord> records(n);
  std::vector<uint64_t> tags(n);
  for (size_t i = 0; i < n; ++i) {
    CacheRecord& r = records[i];
    r = CacheRecord{};
    // Near one plane, as records on a floor: most face each other and lie on each other's tangent planes.
    r.position[0] = 2.0f * unit(rng);
    r.position[1] = 2.0f * unit(rng);
    r.position[2] = 0.0f;
    // Half face straight up (Ward's weight then reaches exactly a radii: the grid's bound is met), half tilted.
    const float tilt = unit(rng) < 0.5f ? 0.0f : 0.2f;
    glm::vec3 normal(tilt * (unit(rng) - 0.5f), tilt * (unit(rng) - 0.5f), 1.0f);
    normal = glm::normalize(normal);
    for (int a = 0; a < 3; ++a) r.normal[a] = normal[a];
    r.radius = 0.004f * std::pow(100.0f, unit(rng));
    for (float& h : r.horizon) h = unit(rng) < 0.2f ? 0.5f * r.radius : 1e30f;
    tags[i] = i * 6 / n;  // six key frames of 500 records
  }
  const float accuracy = 0.3f;
  const std::vector<char> keep = records_not_reached_earlier(records, tags, accuracy);
  size_t kept = 0, dropped = 0;
  std::vector<char> expected(n, 1);
  for (size_t i = 0; i < n; ++i) {
    const PixelGeometry at{record_position(records[i]), record_normal(records[i]), true};
    for (size_t k = 0; k < n && tags[k] < tags[i] && expected[i]; ++k) {
      if (!expected[k]) continue;
      const glm::vec3 pk = record_position(records[k]), nk = record_normal(records[k]);
      if (record_reaches_pixel(records[k], ward_weight(at.p, at.n, pk, nk, records[k].radius), accuracy, at, pk, nk))
        expected[i] = 0;
    }
    (expected[i] ? kept : dropped) += 1;
  }
  EXPECT_EQ(keep, expected) << kept << " kept, " << dropped << " dropped";
  EXPECT_GT(dropped, n / 10) << kept << " kept, " << dropped << " dropped";  // the case tests something: many records are reached
  EXPECT_GT(kept, n / 10);
}

// Format 3's header: magic, format, record size, rcsplat version, fingerprints and frames, device, record times.
constexpr size_t kHeader = 16 + 4 + 4 + 32 + 3 * 8 + 64 + 24;

TEST(CacheFile, EveryBadFileIsRefusedByNameBeforeAnyFrame) {
  const fs::path dir = test::scratch_dir();
  WalkthroughRequest writer = orbit(dir);
  writer.last_frame = 1;
  writer.render.outputs = {(dir / "w%d.exr").string()};
  writer.render.cache_out = (dir / "good.cache").string();
  ASSERT_NO_THROW(render_walkthrough(writer));
  const std::string good = read_bytes(writer.render.cache_out);
  struct Case {
    std::string name, bytes, expected;
    std::function<void(WalkthroughRequest&)> change;
  };
  std::vector<Case> cases;
  auto patched = [&](size_t at, char value, bool sealed) {
    std::string b = good;
    b[at] = value;
    if (sealed) reseal(b);
    return b;
  };
  cases.push_back(
      {"text", "root:x:0:0:root:/root:/bin/bash\n" + std::string(200, 'x'), "not an rcsplat cache file", {}});
  cases.push_back({"short", good.substr(0, 60), "too short", {}});
  cases.push_back({"version", patched(16, 9, true), "cache format version 9", {}});
  cases.push_back({"rcsplat version", patched(24, '7', true), "written by rcsplat 7", {}});
  cases.push_back({"truncated", good.substr(0, good.size() - 100), "truncated or padded", {}});
  cases.push_back({"padded", good + "extra", "truncated or padded", {}});
  cases.push_back({"damaged", patched(200, char(good[200] ^ 1), false), "damaged: its checksum", {}});
  {
    std::string b = good;
    const float negative = -1.0f;
    std::memcpy(b.data() + kHeader + 8 + 160 * 3 + 12, &negative, 4);  // record 3's radius
    reseal(b);
    cases.push_back({"radius", b, "record 3 holds numbers out of range", {}});
  }
  {
    // A count that claims more than the file holds, sealed: refused before anything is allocated for it.
    std::string b = good;
    const uint64_t huge = uint64_t(1) << 60;
    std::memcpy(b.data() + kHeader, &huge, 8);
    reseal(b);
    cases.push_back({"count", b, "truncated or padded", {}});
  }
  {
    // The light guide's first cluster (after the records and the empty maps' sections) with a negative radius.
    uint64_t records = 0;
    std::memcpy(&records, good.data() + kHeader, 8);
    std::string b = good;
    const float negative = -1.0f;
    std::memcpy(b.data() + kHeader + 8 + records * 168 + 16 + 20 + 12 + 20 + 12, &negative, 4);
    reseal(b);
    cases.push_back({"cluster", b, "light guide cluster 0 holds numbers out of range", {}});
  }
  {
    // The time the records hold (format 3, after the device's name): an animation below -1, then a still scene's
    // file read as a moving one's.
    std::string b = good;
    const int32_t animation = -2;
    std::memcpy(b.data() + kHeader - 24, &animation, 4);
    reseal(b);
    cases.push_back({"times", b, "the time its records hold is out of range (animation -2", {}});
    b = good;
    const int32_t moved = 0;
    const double fps = 24.0;
    std::memcpy(b.data() + kHeader - 24, &moved, 4);
    std::memcpy(b.data() + kHeader - 16, &fps, 8);
    reseal(b);
    cases.push_back({"moving", b, "its records hold the scene moved by animations[0], and this render draws the "
                     "scene standing still", {}});
  }
  cases.push_back({"scene", good, "written for another scene",
                   [](WalkthroughRequest& o) { o.render.environment.sky = glm::vec3(0.1f); }});
  cases.push_back({"settings", good, "written with other settings",
                   [](WalkthroughRequest& o) { o.render.settings.cache.accuracy = 0.5f; }});
  cases.push_back({"cap", good, "more than the 10 kept at most", [](WalkthroughRequest& o) { o.render.settings.kept_records_capacity = 10; }});
  for (const Case& c : cases) {
    const std::string path = (dir / (c.name + ".cache")).string();
    test::write_file(path, c.bytes);
    WalkthroughRequest reader = orbit(dir);
    reader.render.outputs = {(dir / (c.name + "_%d.exr")).string()};
    reader.render.cache_in = path;
    reader.last_frame = 1;
    if (c.change) c.change(reader);
    try {
      render_walkthrough(reader);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << c.name << ": " << message;
      EXPECT_NE(message.find(c.expected), std::string::npos) << c.name << ": " << message;
    }
    EXPECT_FALSE(fs::exists(dir / (c.name + "_0.exr"))) << c.name << ": a frame was written";
  }
}

}  // namespace
}  // namespace rcsplat
