#include "sequence/cache_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "util/atomic_file.h"
#include "util/error.h"

namespace rcsplat {
namespace {

constexpr char kMagic[16] = "rcsplat cache\0\0";
constexpr uint32_t kFormatVersion = 3;
constexpr size_t kVersionBytes = 32, kDeviceBytes = 64, kTimesBytes = 4 + 4 + 8 + 8;
constexpr size_t kHeaderBytes = 16 + 4 + 4 + kVersionBytes + 8 * 3 + kDeviceBytes + kTimesBytes;
constexpr size_t kPerRecordBytes = sizeof(CacheRecord) + sizeof(uint64_t);
// A new field of CacheSettings must join settings_fingerprint below (and a new field of CacheRecord, the format).
static_assert(sizeof(CacheSettings) == 56, "a cache setting was added: fingerprint it in settings_fingerprint");
static_assert(sizeof(CacheRecord) == 160, "the record changed: raise kFormatVersion");
static_assert(sizeof(PhotonHit) == 64 && sizeof(GuideCluster) == 48, "a photon or cluster changed: raise kFormatVersion");

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

bool photon_in_range(const PhotonHit& p) {
  if (!finite_all(p.position, 3) || !finite_all(p.normal, 3) || !finite_all(p.flux, 3) || !finite_all(p.incident, 3))
    return false;
  bool ok = p.hit != 0 && p.landing >= 0;
  for (int c = 0; c < 3; ++c) ok = ok && p.flux[c] >= 0.0f && p.incident[c] >= 0.0f;
  return ok;
}

bool cluster_in_range(const GuideCluster& c) {
  if (!finite_all(c.centre, 3) || !finite_all(&c.radius, 1) || !finite_all(c.flux, 3) || !finite_all(c.normal, 3))
    return false;
  return c.radius >= 0.0f && c.flux[0] >= 0.0f && c.flux[1] >= 0.0f && c.flux[2] >= 0.0f;
}

// The file's bytes after the header, read in order; every read is checked against what is left, so a count the file
// claims is never believed past its size.
class Body {
 public:
  Body(const std::string& bytes, size_t at, std::function<void()> short_file)
      : bytes_(bytes), at_(at), short_(std::move(short_file)) {}
  template <typename T>
  T value() {
    need(sizeof(T));
    return take<T>(bytes_, at_);
  }
  // n items of T, after checking that the file holds them.
  template <typename T>
  std::vector<T> items(uint64_t n) {
    if (n > (bytes_.size() - at_) / sizeof(T)) short_();
    std::vector<T> v(static_cast<size_t>(n));
    if (n) std::memcpy(v.data(), bytes_.data() + at_, size_t(n) * sizeof(T));
    at_ += size_t(n) * sizeof(T);
    return v;
  }
  size_t left() const { return bytes_.size() - at_; }

 private:
  void need(size_t n) {
    if (n > bytes_.size() - at_) short_();
  }
  const std::string& bytes_;
  size_t at_;
  std::function<void()> short_;
};

}  // namespace

CacheFileLimits cache_file_limits(const RenderSettings& s) {
  CacheFileLimits l;
  l.records = s.kept_records_capacity;
  l.radiance_floats = size_t(HSH_RECORD_PARTS) * 3 * size_t(s.hsh_order) * size_t(s.hsh_order);
  // Each path lands at most bounces - 1 times after its first reflection (render/indirect_photons.cpp's rounds).
  const size_t landings = s.bounces > 1 ? s.bounces - 1 : 0;
  const size_t paths = s.photon_paths ? size_t(s.photon_paths)
                                      : size_t(kPhotonRounds) * std::max<size_t>(kPhotonMapPhotons / std::max<size_t>(landings, 1), 1024);
  l.photons = paths * landings;
  l.caustic_photons = s.caustic_photons;  // one landing a path, after its glossy reflection
  return l;
}

uint64_t scene_fingerprint(const Scene& s) {
  Fnv h;
  h.array(s.positions);
  h.array(s.normals);
  h.array(s.uvs);
  h.array(s.colors);
  // Features added later enter only where a scene has them, so that older scenes keep their fingerprints.
  if (!s.tangents.empty()) h.array(s.tangents);
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
    if (m.emissive_texture >= 0 || m.normal_texture >= 0 || m.alpha_blend || m.specular_texture >= 0) {
      h.value(m.alpha_blend);
      h.value(m.specular_texture);
      h.value(m.emissive_texture);
      h.value(m.normal_texture);
      h.value(m.normal_scale);
    }
    if (m.transmission > 0.0f) {  // glass (older files' scenes had none, and keep their hashes)
      h.value(m.transmission);
      h.value(m.transmission_texture);
      h.value(m.ior);
      h.value(m.thickness);
      h.value(m.attenuation_color);
      h.value(m.attenuation_distance);
    }
    if (m.layered()) {  // layers (older files' scenes had none, and keep their hashes)
      h.value(m.specular_color);
      h.value(m.specular_color_texture);
      h.value(m.clearcoat);
      h.value(m.clearcoat_texture);
      h.value(m.clearcoat_roughness);
      h.value(m.clearcoat_roughness_texture);
      h.value(m.clearcoat_normal_texture);
      h.value(m.clearcoat_normal_scale);
      h.value(m.sheen_color);
      h.value(m.sheen_color_texture);
      h.value(m.sheen_roughness);
      h.value(m.sheen_roughness_texture);
    }
  }
  h.value(uint64_t(s.textures.size()));
  for (const SceneTexture& t : s.textures) {
    h.value(t.width);
    h.value(t.height);
    h.array(t.rgba);
    h.value(t.wrap_s);
    h.value(t.wrap_t);
    h.value(t.nearest);
    if (!t.mipmaps) h.value(t.mipmaps);  // a later field: hashed where it differs from its default
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
  if (s.glass_light.caustics) {  // a later setting: hashed only where asked for, so older files keep their hashes
    h.value(s.glass_light.photons);
    h.value(s.glass_light.neighbours);
  }
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
  if (c.placement_lines) h.value(c.placement_lines);  // 0 leaves the fingerprints of files written before it alone
  for (unsigned v :
       {k.seed, k.bounces, k.photon_paths, k.photon_neighbours, k.caustic_photons, k.sub_pixel_side, k.hsh_order})
    h.value(v);
  h.value(k.bounce_method);
  h.value(k.short_ray_paths);
  h.value(k.photon_min_support);
  return h.get();
}

namespace {

// The bytes of a vector (none for an empty one, whose data() may be null).
template <typename T>
void put_bytes(std::string& out, const std::vector<T>& items) {
  if (!items.empty()) out.append(reinterpret_cast<const char*>(items.data()), items.size() * sizeof(T));
}

void put_records(std::string& out, const KeptRecords& kept) {
  put_bytes(out, kept.records());
  put_bytes(out, kept.last_used());
}

template <typename T>
void put_items(std::string& out, const std::vector<T>& items) {
  put(out, uint64_t(items.size()));
  put_bytes(out, items);
}

}  // namespace

void write_cache_file(const std::string& path, const KeptCache& kept, const CacheFileIdentity& identity) {
  std::string out;
  const KeptLight& light = kept.light;
  out.reserve(kHeaderBytes + (kept.irradiance.size() + kept.radiance.size()) * kPerRecordBytes +
              kept.radiance.payload().size() * sizeof(float) +
              (light.photons.size() + light.caustic_photons.size()) * sizeof(PhotonHit) + 256);
  out.append(kMagic, sizeof kMagic);
  put(out, kFormatVersion);
  put(out, uint32_t(sizeof(CacheRecord)));
  put_fixed(out, RCSPLAT_VERSION, kVersionBytes);
  put(out, identity.scene);
  put(out, identity.settings);
  put(out, uint64_t(kept.irradiance.frames_begun()));
  put_fixed(out, identity.device, kDeviceBytes);
  put(out, int32_t(kept.times.animation));
  put(out, uint32_t(kept.times.by_key_frame));
  put(out, kept.times.fps);
  put(out, kept.times.time);

  put(out, uint64_t(kept.irradiance.size()));
  put_records(out, kept.irradiance);

  put(out, uint64_t(kept.radiance.size()));
  put(out, uint32_t(kept.radiance.payload_per_record()));
  put(out, kept.radiance.largest_radiance());
  put_records(out, kept.radiance);
  put_bytes(out, kept.radiance.payload());

  put(out, uint32_t(light.has_photon_map));
  put(out, uint64_t(light.photon_paths));
  put_items(out, light.photons);
  put(out, uint32_t(light.has_caustic_map));
  put_items(out, light.caustic_photons);
  put(out, uint32_t(light.has_guide));
  put(out, uint64_t(light.guide_hits));
  put_items(out, light.guide_clusters);

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
                     const CacheFileLimits& limits, KeptCache& into) {
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
  const uint64_t frames = take<uint64_t>(head, at);
  at += kDeviceBytes;  // the device that computed them: for a person reading the file
  RecordTimes times;
  times.animation = take<int32_t>(head, at);
  const uint32_t by_key_frame = take<uint32_t>(head, at);
  times.by_key_frame = by_key_frame != 0;
  times.fps = take<double>(head, at);
  times.time = take<double>(head, at);

  // The largest file these settings can have written, before the file is read whole.
  const uint64_t most = kHeaderBytes + 2 * (8 + uint64_t(limits.records) * kPerRecordBytes) + 16 +
                        uint64_t(limits.records) * limits.radiance_floats * sizeof(float) +
                        (uint64_t(limits.photons) + limits.caustic_photons) * sizeof(PhotonHit) +
                        GUIDE_MAX_CLUSTERS * sizeof(GuideCluster) + 64;
  if (size > most)
    fail(std::to_string(size) + " bytes, more than these settings' records and photons can fill (" +
         std::to_string(most) + " bytes at most with --kept-records " + std::to_string(limits.records) + ")");
  std::string bytes(size, '\0');
  file.seekg(0);
  if (!file.read(bytes.data(), std::streamsize(bytes.size()))) fail("cannot read the cache file");
  auto truncated = [&] { fail("truncated or padded: its counts do not fit its " + std::to_string(size) + " bytes"); };

  // The structure first: every count against the bytes left, nothing believed yet.
  Body body(bytes, kHeaderBytes, truncated);
  KeptRecords::Contents irradiance, radiance;
  uint64_t n = body.value<uint64_t>();
  irradiance.records = body.items<CacheRecord>(n);
  irradiance.last_used = body.items<uint64_t>(n);
  n = body.value<uint64_t>();
  const uint32_t floats = body.value<uint32_t>();
  radiance.payload_per_record = floats;
  radiance.largest_radiance = body.value<float>();
  radiance.records = body.items<CacheRecord>(n);
  radiance.last_used = body.items<uint64_t>(n);
  if (floats && n > body.left() / (uint64_t(floats) * sizeof(float))) truncated();
  radiance.payload = body.items<float>(n * floats);
  KeptLight light;
  light.has_photon_map = body.value<uint32_t>() != 0;
  light.photon_paths = body.value<uint64_t>();
  light.photons = body.items<PhotonHit>(body.value<uint64_t>());
  light.has_caustic_map = body.value<uint32_t>() != 0;
  light.caustic_photons = body.items<PhotonHit>(body.value<uint64_t>());
  light.has_guide = body.value<uint32_t>() != 0;
  light.guide_hits = body.value<uint64_t>();
  light.guide_clusters = body.items<GuideCluster>(body.value<uint64_t>());
  if (body.left() != 8) truncated();

  Fnv sum;
  sum.bytes(bytes.data(), bytes.size() - 8);
  at = bytes.size() - 8;
  if (take<uint64_t>(bytes, at) != sum.get()) fail("damaged: its checksum does not match its contents");
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

  // The time the records hold: a scene that stands still, or an animation's frames at a rate a walkthrough can ask for.
  const bool times_ok = times.animation < 0
                            ? times.animation == -1 && by_key_frame == 0 && times.fps == 0.0 && times.time == 0.0
                            : by_key_frame <= 1 && times.fps > 0.0 && times.fps <= 1000.0 && std::isfinite(times.time) &&
                                  (by_key_frame ? times.time == 0.0 : times.time >= 0.0);
  if (!times_ok)
    fail("the time its records hold is out of range (animation " + std::to_string(times.animation) + ", " +
         std::to_string(times.fps) + " frames/s, " + std::to_string(times.time) + " s)");

  // What these settings can make, then every number.
  for (const auto* kind : {&irradiance, &radiance})
    if (kind->records.size() > limits.records)
      fail(std::to_string(kind->records.size()) + (kind == &irradiance ? " irradiance" : " radiance") +
           " records, more than the " + std::to_string(limits.records) + " kept at most (--kept-records)");
  if (!radiance.records.empty() && floats != limits.radiance_floats)
    fail("radiance records of " + std::to_string(floats) + " coefficients; these settings' HSH order makes " +
         std::to_string(limits.radiance_floats));
  if (light.photons.size() > limits.photons || light.caustic_photons.size() > limits.caustic_photons ||
      light.guide_clusters.size() > GUIDE_MAX_CLUSTERS)
    fail("more photons or light guide clusters than these settings make");
  for (const auto* kind : {&irradiance, &radiance}) {
    const char* name = kind == &irradiance ? "record " : "radiance record ";
    for (size_t i = 0; i < kind->records.size(); ++i) {
      if (!record_in_range(kind->records[i])) fail(name + std::to_string(i) + " holds numbers out of range");
      if (kind->last_used[i] > frames) fail(name + std::to_string(i) + " was used after the file's last frame");
    }
  }
  if (!finite_all(radiance.payload.data(), radiance.payload.size()) || !std::isfinite(radiance.largest_radiance) ||
      radiance.largest_radiance < 0.0f)
    fail("radiance records' coefficients hold numbers out of range");
  for (const std::vector<PhotonHit>* photons : {&light.photons, &light.caustic_photons})
    for (size_t i = 0; i < photons->size(); ++i)
      if (!photon_in_range((*photons)[i]))
        fail(std::string(photons == &light.photons ? "photon " : "caustic photon ") + std::to_string(i) +
             " holds numbers out of range");
  for (size_t i = 0; i < light.guide_clusters.size(); ++i)
    if (!cluster_in_range(light.guide_clusters[i]))
      fail("light guide cluster " + std::to_string(i) + " holds numbers out of range");
  if ((!light.has_photon_map && !light.photons.empty()) || (!light.has_caustic_map && !light.caustic_photons.empty()) ||
      (!light.has_guide && !light.guide_clusters.empty()))
    fail("photons or clusters of a map it says is absent");

  into.irradiance.restore(key, std::move(irradiance), frames);
  into.radiance.restore(key, std::move(radiance), frames);
  into.light = std::move(light);
  into.times = times;
}

}  // namespace rcsplat
