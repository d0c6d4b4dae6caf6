// Cache files (issue 42, item 3; render/cache_file.h): records round-trip bit for bit, a process that reads the file
// renders the next frame as the writer would have, and every bad file is refused by name before any frame.
#include "render/cache_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "cli/commands.h"
#include "image/image_io.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
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

AnimateOptions orbit(const fs::path& dir) {
  AnimateOptions o;
  o.render.settings = test::one_bounce_one_sample();
  o.render.settings.width = o.render.settings.height = 40;
  o.render.settings.light_samples = 4;
  o.orbit_seconds = 4.0;
  o.orbit_degrees = 40.0;
  o.fps = 2.0;
  o.render.outputs = {(dir / "f%d.exr").string()};
  return o;
}

TEST(CacheFile, RecordsRoundTripBitForBit) {
  const Scene scene = make_cornell_box();
  RenderSettings s = test::one_bounce_one_sample();
  s.width = s.height = 40;
  s.keep_records = true;
  Renderer renderer(test::gpu(), scene);
  const FramePlan plan = renderer.plan(s);
  renderer.render(plan);
  renderer.render(plan);
  const KeptRecords& kept = renderer.kept_records();
  ASSERT_GT(kept.size(), 100u);
  const KeptRecordsKey key = kept_records_key(plan.frame);
  const CacheFileIdentity identity{scene_fingerprint(scene), settings_fingerprint(key), "test"};
  const std::string path = test::scratch_dir() + "/cornell.cache";
  write_cache_file(path, kept, identity);
  KeptRecords read(1u << 20);
  read_cache_file(path, identity, key, 1u << 20, read);
  ASSERT_EQ(read.size(), kept.size());
  EXPECT_EQ(std::memcmp(read.records().data(), kept.records().data(), kept.size() * sizeof(CacheRecord)), 0);
  EXPECT_EQ(read.last_used(), kept.last_used());
  EXPECT_EQ(read.frames_begun(), kept.frames_begun());
  EXPECT_EQ(read_bytes(path).size(), 152 + kept.size() * 168 + 8);
}

// A walk rendered in one process, and the same walk split at frame 2 into two processes joined by a cache file: the
// frames after the split are the same bits.
TEST(CacheFile, ARenderFromALoadedCacheIsTheWritersNextFrame) {
  const fs::path dir = test::scratch_dir();
  AnimateOptions whole = orbit(dir / "whole");
  fs::create_directories(dir / "whole");
  whole.last_frame = 3;
  ASSERT_EQ(run_animate(whole), 0);
  fs::create_directories(dir / "split");
  AnimateOptions before = orbit(dir / "split");
  before.last_frame = 2;
  before.render.cache_out = (dir / "walk.cache").string();
  ASSERT_EQ(run_animate(before), 0);
  AnimateOptions after = orbit(dir / "split");
  after.first_frame = after.last_frame = 3;
  after.render.cache_in = before.render.cache_out;
  ASSERT_EQ(run_animate(after), 0);
  int w = 0, h = 0;
  for (const char* f : {"f2.exr", "f3.exr"})
    EXPECT_EQ(read_exr_rgb((dir / "whole" / f).string(), w, h), read_exr_rgb((dir / "split" / f).string(), w, h)) << f;
  // Without the file, frame 3 alone is a fresh cache's: other bits.
  AnimateOptions alone = orbit(dir / "alone");
  fs::create_directories(dir / "alone");
  alone.first_frame = alone.last_frame = 3;
  ASSERT_EQ(run_animate(alone), 0);
  EXPECT_NE(read_exr_rgb((dir / "alone/f3.exr").string(), w, h), read_exr_rgb((dir / "whole/f3.exr").string(), w, h));
}

TEST(CacheFile, EveryBadFileIsRefusedByNameBeforeAnyFrame) {
  const fs::path dir = test::scratch_dir();
  AnimateOptions writer = orbit(dir);
  writer.last_frame = 1;
  writer.render.outputs = {(dir / "w%d.exr").string()};
  writer.render.cache_out = (dir / "good.cache").string();
  ASSERT_EQ(run_animate(writer), 0);
  const std::string good = read_bytes(writer.render.cache_out);
  struct Case {
    std::string name, bytes, expected;
    std::function<void(AnimateOptions&)> change;
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
    std::memcpy(b.data() + 152 + 160 * 3 + 12, &negative, 4);  // record 3's radius
    reseal(b);
    cases.push_back({"radius", b, "record 3 holds numbers out of range", {}});
  }
  cases.push_back({"scene", good, "written for another scene",
                   [](AnimateOptions& o) { o.render.environment.sky = glm::vec3(0.1f); }});
  cases.push_back({"settings", good, "written with other settings",
                   [](AnimateOptions& o) { o.render.settings.cache.accuracy = 0.5f; }});
  cases.push_back({"cap", good, "more than the 10 kept at most", [](AnimateOptions& o) { o.kept_records = 10; }});
  for (const Case& c : cases) {
    const std::string path = (dir / (c.name + ".cache")).string();
    test::write_file(path, c.bytes);
    AnimateOptions reader = orbit(dir);
    reader.render.outputs = {(dir / (c.name + "_%d.exr")).string()};
    reader.render.cache_in = path;
    reader.last_frame = 1;
    if (c.change) c.change(reader);
    try {
      run_animate(reader);
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
