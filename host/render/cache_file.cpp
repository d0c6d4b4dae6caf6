#include "render/cache_file.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/atomic_file.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr char kMagic[16] = "rcsplat cache\0\0";
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kVersionBytes = 32, kDeviceBytes = 64;
constexpr size_t kHeaderBytes = 16 + 4 + 4 + kVersionBytes + 8 * 4 + kDeviceBytes;
constexpr size_t kPerRecordBytes = sizeof(CacheRecord) + sizeof(uint64_t);
// A new field of CacheSettings must join settings_fingerprint below (and a new field of CacheRecord, the format).
static_assert(sizeof(CacheSettings) == 52, "a cache setting was added: fingerprint it in settings_fingerprint");
static_assert(sizeof(CacheRecord) == 160, "the record changed: raise kFormatVersion");

// FNV-1a, 64 bits.
class Fnv {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    value(uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  uint64_t get() const { return hash_; }

 private:
  uint64_t hash_ = 14695981039346656037ull;
};

void put_fixed(std::string& out, const std::string& text, size_t bytes) {
  std::string field = text.substr(0, bytes);
  field.resize(bytes, '\0');
  out += field;
}
template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
T take(const std::string& in, size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}
std::string take_fixed(const std::string& in, size_t& at, size_t bytes) {
  std::string field = in.substr(at, bytes);
  at += bytes;
  return field.substr(0, field.find('\0'));
}

bool finite_all(const float* v, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// A record a splat can use without harm: every number finite but the horizons (infinite where nothing hides a
// sector), a positive radius and pixel size, a unit normal, irradiance and horizons not negative.
bool record_in_range(const CacheRecord& r) {
  if (!finite_all(r.position, 3) || !finite_all(&r.radius, 1) || !finite_all(r.normal, 3) ||
      !finite_all(r.irradiance, 3) || !finite_all(&r.pixel_size, 1) || !finite_all(r.grad_translation, 9) ||
      !finite_all(r.grad_rotation, 9))
    return false;
  const double normal = std::sqrt(double(r.normal[0]) * r.normal[0] + double(r.normal[1]) * r.normal[1] +
                                  double(r.normal[2]) * r.normal[2]);
  bool ok = r.radius > 0.0f && r.pixel_size > 0.0f && std::fabs(normal - 1.0) < 1e-3;
  for (float e : r.irradiance) ok = ok && e >= 0.0f;
  for (float h : r.horizon) ok = ok && h >= 0.0f;  // infinite where nothing hides a sector; never NaN
  return ok;
}

}  // namespace

uint64_t scene_fingerprint(const Scene& s) {
  Fnv h;
  h.array(s.positions);
  h.array(s.normals);
  h.array(s.uvs);
  h.array(s.colors);
  h.array(s.triangle_material);
  h.value(uint64_t(s.materials.size()));
  for (const SceneMaterial& m : s.materials) {
    h.value(m.base_color);
    h.value(m.base_color_texture);
    h.value(m.emission);
    h.value(m.double_sided);
    h.value(m.alpha_cutoff);
    h.value(m.metallic);
    h.value(m.roughness);
    h.value(m.specular);
    h.value(m.metallic_roughness_texture);
  }
  h.value(uint64_t(s.textures.size()));
  for (const SceneTexture& t : s.textures) {
    h.value(t.width);
    h.value(t.height);
    h.array(t.rgba);
    h.value(t.wrap_s);
    h.value(t.wrap_t);
    h.value(t.nearest);
  }
  h.value(uint64_t(s.lights.size()));
  for (const SceneLight& l : s.lights) {
    h.value(l.type);
    h.value(l.position);
    h.value(l.direction);
    h.value(l.intensity);
    h.value(l.range);
    h.value(l.inner_cone);
    h.value(l.outer_cone);
  }
  h.value(s.environment.width);
  h.value(s.environment.height);
  h.array(s.environment.radiance);
  h.value(s.environment.rotation_degrees);
  return h.get();
}

uint64_t settings_fingerprint(const KeptRecordsKey& k) {
  Fnv h;
  const CacheSettings& c = k.cache;
  h.value(c.accuracy);
  h.value(c.theta_strata);
  h.value(c.phi_strata);
  h.value(c.fine_theta_strata);
  h.value(c.fine_phi_strata);
  h.value(c.min_reach_pixels);
  h.value(c.max_reach_pixels);
  h.value(c.hessian_error);
  h.value(c.adaptive_error);
  h.value(c.coarsest_spacing_pixels);
  h.value(c.finest_spacing_pixels);
  h.value(c.guide_rays);
  h.value(c.guide_photons);
  for (unsigned v : {k.seed, k.bounces, k.photon_paths, k.photon_neighbours, k.caustic_photons, k.sub_pixel_side})
    h.value(v);
  h.value(k.bounce_method);
  h.value(k.short_ray_paths);
  h.value(k.photon_min_support);
  return h.get();
}

void write_cache_file(const std::string& path, const KeptRecords& kept, const CacheFileIdentity& identity) {
  std::string out;
  const std::vector<CacheRecord>& records = kept.records();
  out.reserve(kHeaderBytes + records.size() * kPerRecordBytes + 8);
  out.append(kMagic, sizeof kMagic);
  put(out, kFormatVersion);
  put(out, uint32_t(sizeof(CacheRecord)));
  put_fixed(out, RCSPLAT_VERSION, kVersionBytes);
  put(out, identity.scene);
  put(out, identity.settings);
  put(out, uint64_t(kept.frames_begun()));
  put(out, uint64_t(records.size()));
  put_fixed(out, identity.device, kDeviceBytes);
  out.append(reinterpret_cast<const char*>(records.data()), records.size() * sizeof(CacheRecord));
  out.append(reinterpret_cast<const char*>(kept.last_used().data()), records.size() * sizeof(uint64_t));
  Fnv sum;
  sum.bytes(out.data(), out.size());
  put(out, sum.get());
  write_file_atomically(path, [&](const std::string& temp) -> std::string {
    std::ofstream file(temp, std::ios::binary);
    file.write(out.data(), std::streamsize(out.size()));
    return file.flush() ? "" : "cannot be written";
  });
}

void read_cache_file(const std::string& path, const CacheFileIdentity& expected, const KeptRecordsKey& key,
                     size_t capacity, KeptRecords& into) {
  auto fail = [&](const std::string& problem) { throw Error(path + ": " + problem); };
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail("cannot read the cache file (" + ec.message() + ")");
  if (size < kHeaderBytes + 8) fail("not an rcsplat cache file (" + std::to_string(size) + " bytes: too short)");
  std::ifstream file(path, std::ios::binary);
  std::string head(kHeaderBytes, '\0');
  if (!file.read(head.data(), std::streamsize(head.size()))) fail("cannot read the cache file");
  size_t at = 0;
  if (std::memcmp(head.data(), kMagic, sizeof kMagic) != 0) fail("not an rcsplat cache file");
  at = sizeof kMagic;
  const uint32_t version = take<uint32_t>(head, at), record_bytes = take<uint32_t>(head, at);
  if (version != kFormatVersion)
    fail("cache format version " + std::to_string(version) + "; this rcsplat reads version " +
         std::to_string(kFormatVersion));
  if (record_bytes != sizeof(CacheRecord))
    fail("records of " + std::to_string(record_bytes) + " bytes; this rcsplat's are " +
         std::to_string(sizeof(CacheRecord)));
  const std::string written_by = take_fixed(head, at, kVersionBytes);
  const uint64_t scene = take<uint64_t>(head, at), settings = take<uint64_t>(head, at);
  const uint64_t frames = take<uint64_t>(head, at), count = take<uint64_t>(head, at);
  at += kDeviceBytes;  // the device that computed them: for a person reading the file
  // The size the count claims, before anything is allocated for it.
  if (count > (size - kHeaderBytes - 8) / kPerRecordBytes || kHeaderBytes + count * kPerRecordBytes + 8 != size)
    fail("truncated or padded: " + std::to_string(size) + " bytes where its " + std::to_string(count) +
         " records need " + std::to_string(kHeaderBytes + count * kPerRecordBytes + 8));
  if (count > capacity)
    fail(std::to_string(count) + " records, more than the " + std::to_string(capacity) +
         " kept at most (--kept-records)");
  std::string body(size - kHeaderBytes, '\0');
  if (!file.read(body.data(), std::streamsize(body.size()))) fail("cannot read the cache file");
  Fnv sum;
  sum.bytes(head.data(), head.size());
  sum.bytes(body.data(), body.size() - 8);
  at = body.size() - 8;
  if (take<uint64_t>(body, at) != sum.get()) fail("damaged: its checksum does not match its contents");
  if (written_by != RCSPLAT_VERSION)
    fail("written by rcsplat " + written_by + ", this is " + RCSPLAT_VERSION +
         ": records are computed differently from version to version");
  if (scene != expected.scene)
    fail(
        "written for another scene (or this scene changed since: its geometry, materials, textures, lights or "
        "environment)");
  if (settings != expected.settings)
    fail(
        "written with other settings than this render's (cache settings, seed, bounces, photons, pixel samples); "
        "render with the settings that wrote it");
  std::vector<CacheRecord> records(count);
  std::vector<uint64_t> last_used(count);
  std::memcpy(records.data(), body.data(), count * sizeof(CacheRecord));
  std::memcpy(last_used.data(), body.data() + count * sizeof(CacheRecord), count * sizeof(uint64_t));
  for (uint64_t i = 0; i < count; ++i) {
    if (!record_in_range(records[i])) fail("record " + std::to_string(i) + " holds numbers out of range");
    if (last_used[i] > frames) fail("record " + std::to_string(i) + " was used after the file's last frame");
  }
  into.restore(key, std::move(records), std::move(last_used), frames);
}

}  // namespace rcsplat
