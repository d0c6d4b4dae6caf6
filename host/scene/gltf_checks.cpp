#include "scene/gltf_checks.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "util/byte_size.h"
#include "util/error.h"
#include "util/paths.h"

namespace rcsplat {
namespace {

using nlohmann::json;

std::string mib(uint64_t bytes) {
  if (bytes < (uint64_t(1) << 20)) return std::to_string(bytes) + " bytes";
  return byte_size(double(bytes), bytes >= (uint64_t(1) << 30) ? "GiB" : "MiB");
}

// ---- The scene file itself -------------------------------------------------------------------------------------

std::vector<unsigned char> read_scene_file(const std::string& path, uint64_t max_bytes, const char* limit_name,
                                           HostBudget& budget) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    if (fd >= 0) ::close(fd);
    throw Error(path + ": no such file");
  }
  const uint64_t size = uint64_t(st.st_size);
  if (size > max_bytes) {
    ::close(fd);
    throw Error(path + ": the file is " + mib(size) + "; rcsplat reads at most " + mib(max_bytes) + " of " +
                limit_name);
  }
  budget.charge(size, "the scene file");
  std::vector<unsigned char> bytes(size);
  size_t done = 0;
  while (done < size) {
    const ssize_t got = ::read(fd, bytes.data() + done, size - done);
    if (got <= 0) break;
    done += size_t(got);
  }
  ::close(fd);
  if (done != size) throw Error(path + ": cannot be read (it ended at byte " + std::to_string(done) + ")");
  return bytes;
}

uint32_t u32_at(const std::vector<unsigned char>& b, size_t offset) {
  uint32_t v;
  std::memcpy(&v, b.data() + offset, 4);
  return v;  // GLB is little-endian, as every machine rcsplat runs on
}

constexpr uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

// The GLB container (header, JSON chunk, optional BIN chunk), each part checked with where the file ends.
struct GlbParts {
  size_t json_offset = 0, json_length = 0;
  size_t bin_offset = 0, bin_length = 0;
  bool has_bin = false;
};

GlbParts split_glb(const std::string& path, std::vector<unsigned char>& b) {
  auto fail = [&](const std::string& what) -> void { throw Error(path + ": " + what); };
  const size_t size = b.size();
  if (size == 0) fail("the file is empty; a GLB starts with a 12-byte header (magic 'glTF', version, length)");
  if (size < 12)
    fail("the file ends at byte " + std::to_string(size) +
         ", inside the 12-byte GLB header (magic 'glTF', version, length)");
  if (u32_at(b, 0) != kGlbMagic) fail("does not start with the GLB magic 'glTF': not a binary glTF file");
  if (u32_at(b, 4) != 2)
    fail("is GLB version " + std::to_string(u32_at(b, 4)) + "; rcsplat reads glTF 2.0 (GLB version 2)");
  const size_t length = u32_at(b, 8);
  // Where the chunks must end: the header's length, or the file's end when it is shorter (then the message says
  // which chunk the file ends in).
  const size_t end = std::min(length, size);
  const std::string truncated =
      length > size ? "; the header says the file holds " + std::to_string(length) + " bytes: it is truncated" : "";
  if (length < size) b.resize(length);  // bytes after the stated length belong to no chunk
  if (end < 20)
    fail("the file ends at byte " + std::to_string(end) +
         ", inside the JSON chunk's 8-byte header expected at byte 12 (chunk length, type)" + truncated);
  GlbParts parts;
  parts.json_length = u32_at(b, 12);
  if (u32_at(b, 16) != kJsonChunk)
    fail("the first chunk (byte 12) is not of type JSON; a GLB starts with its JSON chunk");
  parts.json_offset = 20;
  if (parts.json_length == 0) fail("the JSON chunk (byte 12) is empty");
  if (uint64_t(parts.json_offset) + parts.json_length > end)
    fail("the JSON chunk says it holds " + std::to_string(parts.json_length) +
         " bytes from byte 20, but the file ends at byte " + std::to_string(end) + truncated);
  if (parts.json_length % 4)
    fail("the JSON chunk's length, " + std::to_string(parts.json_length) +
         ", is not a multiple of 4 (GLB pads it with spaces)");
  const size_t next = parts.json_offset + parts.json_length;
  if (next == end) {
    if (!truncated.empty())
      fail("the file ends at byte " + std::to_string(end) + ", where a BIN chunk's header was expected" + truncated);
    return parts;
  }
  if (next + 8 > end)
    fail("the file ends at byte " + std::to_string(end) + ", inside the BIN chunk's 8-byte header expected at byte " +
         std::to_string(next) + truncated);
  parts.bin_length = u32_at(b, next);
  if (u32_at(b, next + 4) != kBinChunk)
    fail("the chunk at byte " + std::to_string(next) +
         " is not of type BIN (the only chunk rcsplat reads after the JSON)");
  parts.bin_offset = next + 8;
  if (uint64_t(parts.bin_offset) + parts.bin_length > end)
    fail("the BIN chunk says it holds " + std::to_string(parts.bin_length) + " bytes from byte " +
         std::to_string(parts.bin_offset) + ", but the file ends at byte " + std::to_string(end) + truncated);
  if (parts.bin_length == 0 || parts.bin_length % 4)
    fail("the BIN chunk's length, " + std::to_string(parts.bin_length) + ", is not a positive multiple of 4");
  if (!truncated.empty()) fail("the file ends at byte " + std::to_string(end) + ", after its chunks" + truncated);
  parts.has_bin = true;
  return parts;
}

std::vector<unsigned char> join_glb(const std::vector<unsigned char>& old, const GlbParts& parts, std::string text) {
  while (text.size() % 4) text += ' ';
  std::vector<unsigned char> out;
  auto put = [&](uint32_t v) {
    out.insert(out.end(), reinterpret_cast<unsigned char*>(&v), reinterpret_cast<unsigned char*>(&v) + 4);
  };
  const size_t bin = parts.has_bin ? 8 + parts.bin_length : 0;
  put(kGlbMagic);
  put(2);
  put(uint32_t(12 + 8 + text.size() + bin));
  put(uint32_t(text.size()));
  put(kJsonChunk);
  out.insert(out.end(), text.begin(), text.end());
  if (parts.has_bin)
    out.insert(out.end(), old.begin() + long(parts.bin_offset - 8),
               old.begin() + long(parts.bin_offset + parts.bin_length));
  return out;
}

// ---- The JSON text ------------------------------------------------------------------------------------------------

// JSON nesting deeper than this is refused before it is parsed: tinygltf copies "extras" and "extensions" values
// recursively, and 100,000 nested arrays there overflowed its stack. glTF's own structure is about 8 deep.
constexpr int kMaxJsonDepth = 128;

void check_json_depth(const std::string& path, const unsigned char* text, size_t length) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < length; ++i) {
    const unsigned char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw Error(path + ": the JSON nests arrays and objects more than " + std::to_string(kMaxJsonDepth) +
                    " deep (at byte " + std::to_string(i) + "); a glTF file needs about 8");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// ---- The JSON's objects ------------------------------------------------------------------------------------------

// A JSON number that is a whole number (1, 1.0 or 1e3), as a double; nothing for any other value. No conversion of a
// double beyond int64's range (found by fuzzing: 6.8e69 as an index).
std::optional<double> whole_number(const json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return v.get<double>();
  if (!v.is_number_float()) return std::nullopt;
  const double d = v.get<double>();
  if (!(std::abs(d) < 9.0e15) || d != std::floor(d)) return std::nullopt;
  return d;
}

// Checks the properties rcsplat and tinygltf rely on: required ones present with the right type, indices naming an
// object that exists. Messages name the object as a JSON path would: "meshes[0].primitives[1]".
class JsonChecks {
 public:
  JsonChecks(const std::string& path, const json& doc) : path_(path), doc_(doc) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw Error(path_ + ": " + where + ": " + what);
  }

  size_t count(const char* array) const {
    auto it = doc_.find(array);
    return it != doc_.end() && it->is_array() ? it->size() : 0;
  }

  void top_level() const {
    if (!doc_.is_object()) throw Error(path_ + ": the JSON is not an object; a glTF file is one JSON object");
    auto asset = doc_.find("asset");
    if (asset == doc_.end() || !asset->is_object()) fail("asset", "is required (an object with \"version\": \"2.0\")");
    auto version = asset->find("version");
    if (version == asset->end() || !version->is_string()) fail("asset", "\"version\" is required (\"2.0\")");
    const std::string v = version->get<std::string>();
    if (v.rfind("2.", 0) != 0) fail("asset", "version '" + v + "': rcsplat reads glTF 2.x");
    for (const char* array : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                              "meshes", "nodes", "samplers", "scenes", "skins", "textures"}) {
      auto it = doc_.find(array);
      if (it == doc_.end()) continue;
      if (!it->is_array()) fail(array, "must be an array");
      for (size_t i = 0; i < it->size(); ++i)
        if (!(*it)[i].is_object()) fail(std::string(array) + "[" + std::to_string(i) + "]", "must be an object");
    }
    index(doc_, "scene", "scene", "scenes", false);
  }

  // An optional or required integer property in [lo, hi]; returns it (or fallback).
  int64_t integer(const json& o, const std::string& where, const char* key, bool required, int64_t lo, int64_t hi,
                  int64_t fallback = -1) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) fail(where, std::string("\"") + key + "\" is required");
      return fallback;
    }
    const std::optional<double> whole = whole_number(*it);
    if (!whole) fail(where, std::string("\"") + key + "\" must be an integer");
    const double d = *whole;
    if (d < double(lo) || d > double(hi))
      fail(where, std::string("\"") + key + "\" is " + it->dump() + "; it must lie in " + std::to_string(lo) + ".." +
                      std::to_string(hi));
    return int64_t(d);
  }

  // An index property naming an object of the top-level array `target`.
  int64_t index(const json& o, const std::string& where, const char* key, const char* target, bool required) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) fail(where, std::string("\"") + key + "\" is required (an index into " + target + ")");
      return -1;
    }
    return checked_index(*it, where + "." + key, target);
  }

  int64_t checked_index(const json& v, const std::string& where, const char* target) const {
    const size_t n = count(target);
    const std::optional<double> whole = whole_number(v);
    if (!whole) fail(where, "must be an index into " + std::string(target) + ", not " + v.dump().substr(0, 40));
    const double d = *whole;
    if (d < 0 || d >= double(n))
      fail(where, "is " + v.dump() + ", but the file has " + std::to_string(n) + " " + target);
    return int64_t(d);
  }

  void index_array(const json& o, const std::string& where, const char* key, const char* target, bool required,
                   bool non_empty) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) fail(where, std::string("\"") + key + "\" is required (an array of indices into " + target + ")");
      return;
    }
    if (!it->is_array()) fail(where + "." + key, std::string("must be an array of indices into ") + target);
    if (non_empty && it->empty()) fail(where + "." + key, "must not be empty");
    for (size_t i = 0; i < it->size(); ++i)
      checked_index((*it)[i], where + "." + key + "[" + std::to_string(i) + "]", target);
  }

  const json* object(const json& o, const std::string& where, const char* key, bool required) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) fail(where, std::string("\"") + key + "\" is required (an object)");
      return nullptr;
    }
    if (!it->is_object()) fail(where + "." + key, "must be an object");
    return &*it;
  }

  void string(const json& o, const std::string& where, const char* key, bool required) const {
    auto it = o.find(key);
    if (it == o.end()) {
      if (required) fail(where, std::string("\"") + key + "\" is required (a string)");
      return;
    }
    if (!it->is_string()) fail(where + "." + key, "must be a string");
  }

  template <typename Visit>
  void each(const char* array, Visit visit) const {
    auto it = doc_.find(array);
    if (it == doc_.end()) return;
    for (size_t i = 0; i < it->size(); ++i) visit((*it)[i], std::string(array) + "[" + std::to_string(i) + "]");
  }

  void objects() const {
    static const std::set<int64_t> component_types = {5120, 5121, 5122, 5123, 5125, 5126};
    static const std::set<std::string> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    const int64_t int_max = 2147483647, size_max = int64_t(1) << 53;
    each("accessors", [&](const json& a, const std::string& w) {
      index(a, w, "bufferView", "bufferViews", false);
      integer(a, w, "byteOffset", false, 0, size_max);
      if (!component_types.count(integer(a, w, "componentType", true, 0, int_max)))
        fail(w, "componentType " + a["componentType"].dump() + " is not one of glTF's (5120..5123, 5125, 5126)");
      integer(a, w, "count", true, 1, int_max);
      string(a, w, "type", true);
      if (!types.count(a["type"].get<std::string>()))
        fail(w, "type '" + a["type"].get<std::string>() + "' is not a glTF accessor type");
      if (const json* sparse = object(a, w, "sparse", false)) {
        const std::string s = w + ".sparse";
        integer(*sparse, s, "count", true, 1, int_max);
        const json* indices = object(*sparse, s, "indices", true);
        index(*indices, s + ".indices", "bufferView", "bufferViews", true);
        integer(*indices, s + ".indices", "byteOffset", false, 0, size_max);
        integer(*indices, s + ".indices", "componentType", true, 0, int_max);
        const json* values = object(*sparse, s, "values", true);
        index(*values, s + ".values", "bufferView", "bufferViews", true);
        integer(*values, s + ".values", "byteOffset", false, 0, size_max);
      }
    });
    each("bufferViews", [&](const json& v, const std::string& w) {
      index(v, w, "buffer", "buffers", true);
      integer(v, w, "byteOffset", false, 0, size_max);
      integer(v, w, "byteLength", true, 1, size_max);
      integer(v, w, "byteStride", false, 4, 252);
    });
    each("buffers", [&](const json& b, const std::string& w) {
      integer(b, w, "byteLength", true, 1, size_max);
      string(b, w, "uri", false);
    });
    each("images", [&](const json& im, const std::string& w) {
      string(im, w, "uri", false);
      index(im, w, "bufferView", "bufferViews", false);
      if (!im.contains("uri") && !im.contains("bufferView")) fail(w, "has neither \"uri\" nor \"bufferView\"");
      if (im.contains("bufferView")) string(im, w, "mimeType", true);
    });
    each("textures", [&](const json& t, const std::string& w) {
      index(t, w, "source", "images", false);
      index(t, w, "sampler", "samplers", false);
    });
    each("materials", [&](const json& m, const std::string& w) {
      auto texture = [&](const json& o, const std::string& where, const char* key) {
        if (const json* info = object(o, where, key, false)) index(*info, where + "." + key, "index", "textures", true);
      };
      if (const json* pbr = object(m, w, "pbrMetallicRoughness", false)) {
        texture(*pbr, w + ".pbrMetallicRoughness", "baseColorTexture");
        texture(*pbr, w + ".pbrMetallicRoughness", "metallicRoughnessTexture");
      }
      for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) texture(m, w, key);
    });
    each("meshes", [&](const json& m, const std::string& w) {
      auto prims = m.find("primitives");
      if (prims == m.end() || !prims->is_array() || prims->empty())
        fail(w, "\"primitives\" is required (a non-empty array)");
      for (size_t p = 0; p < prims->size(); ++p) {
        const std::string pw = w + ".primitives[" + std::to_string(p) + "]";
        const json& prim = (*prims)[p];
        if (!prim.is_object()) fail(pw, "must be an object");
        const json* attributes = object(prim, pw, "attributes", true);
        for (auto it = attributes->begin(); it != attributes->end(); ++it)
          checked_index(it.value(), pw + ".attributes." + it.key(), "accessors");
        index(prim, pw, "indices", "accessors", false);
        index(prim, pw, "material", "materials", false);
        integer(prim, pw, "mode", false, 0, 6);
        if (auto targets = prim.find("targets"); targets != prim.end()) {
          if (!targets->is_array()) fail(pw + ".targets", "must be an array of objects");
          for (size_t t = 0; t < targets->size(); ++t) {
            const std::string tw = pw + ".targets[" + std::to_string(t) + "]";
            if (!(*targets)[t].is_object()) fail(tw, "must be an object");
            for (auto it = (*targets)[t].begin(); it != (*targets)[t].end(); ++it)
              checked_index(it.value(), tw + "." + it.key(), "accessors");
          }
        }
      }
    });
    each("nodes", [&](const json& n, const std::string& w) {
      index_array(n, w, "children", "nodes", false, false);
      index(n, w, "mesh", "meshes", false);
      index(n, w, "camera", "cameras", false);
      index(n, w, "skin", "skins", false);
      for (const char* key : {"matrix", "translation", "rotation", "scale", "weights"}) {
        auto it = n.find(key);
        if (it == n.end()) continue;
        if (!it->is_array() || !std::all_of(it->begin(), it->end(), [](const json& v) { return v.is_number(); }))
          fail(w + "." + key, "must be an array of numbers");
      }
      if (const json* ext = object(n, w, "extensions", false))
        if (const json* lights = object(*ext, w + ".extensions", "KHR_lights_punctual", false)) {
          auto defined = doc_.find("extensions");
          size_t light_count = 0;
          if (defined != doc_.end() && defined->is_object()) {
            auto klp = defined->find("KHR_lights_punctual");
            if (klp != defined->end() && klp->is_object() && klp->contains("lights") && (*klp)["lights"].is_array())
              light_count = (*klp)["lights"].size();
          }
          auto light = lights->find("light");
          if (light == lights->end() || !light->is_number() || light->get<double>() < 0 ||
              light->get<double>() >= double(light_count))
            fail(
                w + ".extensions.KHR_lights_punctual",
                "\"light\" must name one of the file's " + std::to_string(light_count) + " KHR_lights_punctual lights");
        }
    });
    each("scenes", [&](const json& s, const std::string& w) { index_array(s, w, "nodes", "nodes", false, false); });
    each("skins", [&](const json& s, const std::string& w) {
      index_array(s, w, "joints", "nodes", true, true);
      index(s, w, "inverseBindMatrices", "accessors", false);
      index(s, w, "skeleton", "nodes", false);
    });
    each("cameras", [&](const json& c, const std::string& w) {
      string(c, w, "type", true);
      const std::string type = c["type"].get<std::string>();
      if (type != "perspective" && type != "orthographic")
        fail(w, "type '" + type + "' is neither perspective nor orthographic");
      const json* p = object(c, w, type.c_str(), true);
      for (const char* key : type == "perspective" ? std::vector<const char*>{"yfov", "znear"}
                                                   : std::vector<const char*>{"xmag", "ymag", "zfar", "znear"})
        if (!p->contains(key) || !(*p)[key].is_number())
          fail(w + "." + type, std::string("\"") + key + "\" is required (a number)");
    });
    each("samplers", [&](const json& s, const std::string& w) {
      for (const char* key : {"magFilter", "minFilter", "wrapS", "wrapT"}) integer(s, w, key, false, 0, 65535);
    });
    each("animations", [&](const json& a, const std::string& w) {
      auto samplers = a.find("samplers");
      if (samplers == a.end() || !samplers->is_array()) fail(w, "\"samplers\" is required (an array)");
      auto channels = a.find("channels");
      if (channels == a.end() || !channels->is_array()) fail(w, "\"channels\" is required (an array)");
      for (size_t s = 0; s < samplers->size(); ++s) {
        const std::string sw = w + ".samplers[" + std::to_string(s) + "]";
        if (!(*samplers)[s].is_object()) fail(sw, "must be an object");
        index((*samplers)[s], sw, "input", "accessors", true);
        index((*samplers)[s], sw, "output", "accessors", true);
      }
      for (size_t c = 0; c < channels->size(); ++c) {
        const std::string cw = w + ".channels[" + std::to_string(c) + "]";
        if (!(*channels)[c].is_object()) fail(cw, "must be an object");
        integer((*channels)[c], cw, "sampler", true, 0, int64_t(samplers->size()) - 1);
        const json* target = object((*channels)[c], cw, "target", true);
        index(*target, cw + ".target", "node", "nodes", false);
        string(*target, cw + ".target", "path", true);
      }
    });
    if (auto ext = doc_.find("extensions"); ext != doc_.end() && ext->is_object())
      if (auto klp = ext->find("KHR_lights_punctual"); klp != ext->end()) {
        auto lights = klp->is_object() ? klp->find("lights") : klp->end();
        if (lights == klp->end() || !lights->is_array())
          fail("extensions.KHR_lights_punctual", "\"lights\" must be an array");
        for (size_t l = 0; l < lights->size(); ++l) {
          const std::string lw = "extensions.KHR_lights_punctual.lights[" + std::to_string(l) + "]";
          if (!(*lights)[l].is_object()) fail(lw, "must be an object");
          string((*lights)[l], lw, "type", true);
        }
      }
  }

  // One parent for each node, no cycles, and the scenes' roots parentless and listed once (glTF 2.0 §3.5.3): the
  // walk then visits every node once, whatever the file.
  void node_graph() const {
    const size_t n = count("nodes");
    std::vector<int64_t> parent(n, -1);
    each("nodes", [&](const json& node, const std::string& w) {
      const int64_t self = std::stoll(w.substr(6));
      auto children = node.find("children");
      if (children == node.end()) return;
      for (const json& c : *children) {
        const int64_t child = int64_t(c.get<double>());
        if (child == self) fail(w, "lists itself as its own child (a cycle)");
        if (parent[size_t(child)] == self) fail(w, "lists nodes[" + std::to_string(child) + "] twice as a child");
        if (parent[size_t(child)] >= 0)
          fail("nodes[" + std::to_string(child) + "]", "has two parents, nodes[" +
                                                           std::to_string(parent[size_t(child)]) + "] and nodes[" +
                                                           std::to_string(self) + "]; glTF allows one");
        parent[size_t(child)] = self;
      }
    });
    // With one parent each, a cycle is a parent chain that comes back: follow each chain once (stamps), iteratively.
    std::vector<int64_t> stamp(n, -1);
    std::vector<bool> done(n, false);
    for (size_t start = 0; start < n; ++start) {
      int64_t at = int64_t(start);
      while (at >= 0 && !done[size_t(at)] && stamp[size_t(at)] != int64_t(start)) {
        stamp[size_t(at)] = int64_t(start);
        at = parent[size_t(at)];
      }
      if (at >= 0 && !done[size_t(at)] && stamp[size_t(at)] == int64_t(start)) {
        std::string chain = "nodes[" + std::to_string(at) + "]";
        for (int64_t up = parent[size_t(at)], steps = 0; up != at && steps < 4; up = parent[size_t(up)], ++steps)
          chain += " -> nodes[" + std::to_string(up) + "]";
        fail("nodes[" + std::to_string(at) + "]", "is its own ancestor (a cycle of parents: " + chain + " ...)");
      }
      for (at = int64_t(start); at >= 0 && !done[size_t(at)]; at = parent[size_t(at)]) done[size_t(at)] = true;
    }
    each("scenes", [&](const json& s, const std::string& w) {
      auto roots = s.find("nodes");
      if (roots == s.end()) return;
      std::set<int64_t> seen;
      for (const json& r : *roots) {
        const int64_t root = int64_t(r.get<double>());
        if (!seen.insert(root).second) fail(w, "lists nodes[" + std::to_string(root) + "] twice");
        if (parent[size_t(root)] >= 0)
          fail(w, "lists nodes[" + std::to_string(root) + "] as a root, but it is a child of nodes[" +
                      std::to_string(parent[size_t(root)]) + "]");
      }
    });
  }

 private:
  const std::string& path_;
  const json& doc_;
};

// ---- Buffers and images ------------------------------------------------------------------------------------------

const char* const kDataUriPrefixes[] = {"data:application/octet-stream;base64,",
                                        "data:application/gltf-buffer;base64,",
                                        "data:image/jpeg;base64,",
                                        "data:image/png;base64,",
                                        "data:image/bmp;base64,",
                                        "data:image/gif;base64,",
                                        "data:text/plain;base64,"};

bool is_data_uri(const std::string& uri) { return uri.rfind("data:", 0) == 0; }

// A data URI's decoded size, checked to be base64 of a media type tinygltf decodes.
uint64_t data_uri_bytes(const std::string& file, const std::string& what, const std::string& uri) {
  std::string prefix;
  for (const char* p : kDataUriPrefixes)
    if (uri.rfind(p, 0) == 0) prefix = p;
  if (prefix.empty()) {
    const std::string head = uri.substr(0, std::min<size_t>(uri.find(','), 60));
    throw Error(file + ": " + what + ": the data URI '" + head +
                ",...' is not read; rcsplat reads base64 data URIs "
                "of application/octet-stream, application/gltf-buffer and image/png, jpeg, bmp or gif");
  }
  const size_t begin = prefix.size();
  size_t length = uri.size() - begin;
  while (length > 0 && uri[begin + length - 1] == '=') --length;
  for (size_t i = 0; i < length; ++i) {
    const char c = uri[begin + i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/'))
      throw Error(file + ": " + what + ": the data URI holds a character that is not base64 at character " +
                  std::to_string(begin + i));
  }
  if (length == 0) throw Error(file + ": " + what + ": the data URI holds no data");
  return uint64_t(length) * 3 / 4;
}

// The path tinygltf 2.7 asks its file callbacks for: its base directory joined with '/' to the URI, which it decodes
// with '+' as a space. (A malformed escape decodes otherwise there; such a key is simply never found: refused.)
std::string join_like_tinygltf(const std::string& base, std::string uri) {
  std::replace(uri.begin(), uri.end(), '+', ' ');
  const std::string decoded = AssetAccess::decode_uri(uri);
  if (base.empty()) return decoded;
  return base.back() == '/' ? base + decoded : base + "/" + decoded;
}

}  // namespace

uint64_t SceneLimits::host_budget() const {
  if (host_memory_bytes) return host_memory_bytes;
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  return physical > 0.0 ? uint64_t(physical * 0.75) : uint64_t(8) << 30;
}

HostBudget::HostBudget(const std::string& scene_file, const SceneLimits& limits)
    : scene_file_(scene_file), budget_(limits.host_budget()) {}

void HostBudget::charge(uint64_t bytes, const std::string& what) {
  check_fits(bytes, what);
  used_ += bytes;
}

void HostBudget::check_fits(uint64_t bytes, const std::string& what) const {
  if (bytes > budget_ - std::min(used_, budget_))
    throw Error(scene_file_ + ": " + what + " needs " + mib(bytes) + " of host memory, beyond the scene's budget of " +
                mib(budget_) + " (" + mib(used_) + " taken already; --max-host-memory sets it)");
}

CheckedGltf check_gltf(const AssetAccess& access, const SceneLimits& limits, HostBudget& budget) {
  const std::string& path = access.scene_file();
  CheckedGltf out;
  out.binary = lower_extension(path) == ".glb";
  out.base_dir = access.scene_folder().string();
  std::vector<unsigned char> bytes =
      out.binary ? read_scene_file(path, uint64_t(1) << 32, "GLB (its length field has 32 bits)", budget)
                 : read_scene_file(path, limits.max_json_bytes,
                                   "glTF JSON (--max-host-memory does not change it; put "
                                   "large data in .bin buffers)",
                                   budget);
  if (!out.binary && bytes.size() >= 4 && u32_at(bytes, 0) == kGlbMagic)
    throw Error(path + ": holds a binary glTF (GLB) but is named .gltf; name it .glb");
  GlbParts parts;
  const unsigned char* text = bytes.data();
  size_t text_length = bytes.size();
  if (out.binary) {
    parts = split_glb(path, bytes);
    text = bytes.data() + parts.json_offset;
    text_length = parts.json_length;
    if (text_length > limits.max_json_bytes)
      throw Error(path + ": the JSON chunk is " + mib(text_length) + "; rcsplat reads at most " +
                  mib(limits.max_json_bytes));
  }
  if (text_length == 0) throw Error(path + ": the file is empty; a glTF file is a JSON object");
  budget.charge(text_length * 8, "the glTF JSON (parsed twice, about 4 times its size each)");
  check_json_depth(path, text, text_length);
  json doc;
  try {
    doc = json::parse(text, text + text_length);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond double's range (found by fuzzing)
    std::string what = e.what();
    const size_t close = what.find("] ");
    if (close != std::string::npos) what = what.substr(close + 2);
    throw Error(path + ": is not valid JSON: " + what);
  }
  const JsonChecks checks(path, doc);
  checks.top_level();
  checks.objects();
  checks.node_graph();

  // Buffers: where each one's bytes come from, under the access policy; an unread buffer needs none.
  bool rewritten = false;
  std::vector<bool> buffer_read(checks.count("buffers"), false);
  checks.each("bufferViews",
              [&](const json& v, const std::string&) { buffer_read[size_t(v["buffer"].get<double>())] = true; });
  for (size_t i = 0; i < buffer_read.size(); ++i) {
    json& buffer = doc["buffers"][i];
    const uint64_t length = buffer["byteLength"].get<uint64_t>();
    std::string what = "buffers[" + std::to_string(i) + "]";
    if (!buffer.contains("uri")) {
      if (out.binary && i == 0) {
        if (!parts.has_bin) {
          if (!buffer_read[i]) {
            buffer["uri"] = "data:application/octet-stream;base64,AA==";  // nothing reads it: stand in one byte
            buffer["byteLength"] = 1;
            rewritten = true;
            continue;
          }
          throw Error(path + ": " + what + " is the GLB's BIN chunk, but the file has none");
        }
        if (length > parts.bin_length)
          throw Error(path + ": " + what + " says it holds " + std::to_string(length) +
                      " bytes, but the BIN chunk holds " + std::to_string(parts.bin_length));
        continue;
      }
      if (buffer_read[i])
        throw Error(path + ": " + what +
                    " has no \"uri\" but a buffer view reads it (only a GLB's first buffer may "
                    "leave it out)");
      buffer["uri"] = "data:application/octet-stream;base64,AA==";  // valid glTF: a buffer nothing reads
      buffer["byteLength"] = 1;
      rewritten = true;
      continue;
    }
    const std::string uri = buffer["uri"].get<std::string>();
    what += " '" + uri.substr(0, 80) + "'";
    if (is_data_uri(uri)) {
      const uint64_t decoded = data_uri_bytes(path, what, uri);
      if (decoded != length)
        throw Error(path + ": " + what.substr(0, what.find(' ')) + ": its data URI holds " + std::to_string(decoded) +
                    " bytes but byteLength says " + std::to_string(length));
      budget.charge(decoded * 2, what.substr(0, what.find(' ')) + " (decoded from its data URI)");
      continue;
    }
    const std::filesystem::path file = access.resolve(what.substr(0, what.find(' ')), uri);
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(file, ec);
    if (ec || size < length)
      throw Error(path + ": " + what + ": byteLength says " + std::to_string(length) + " bytes, but the file holds " +
                  std::to_string(ec ? 0 : size) + ": it is truncated or not this scene's buffer");
    budget.charge(length, what);
    out.files[join_like_tinygltf(out.base_dir, uri)] = {file, length, what};
  }
  // Images: a file or a data URI (a buffer view's bytes are counted with its buffer). Decoding is checked later,
  // from each image's header, before any pixel is allocated (gltf_loader.cpp).
  checks.each("images", [&](const json& image, const std::string& w) {
    if (!image.contains("uri")) return;
    const std::string uri = image["uri"].get<std::string>();
    const std::string what = w + " '" + uri.substr(0, 80) + "'";
    if (is_data_uri(uri)) {
      budget.charge(data_uri_bytes(path, what, uri), w + " (decoded from its data URI)");
      return;
    }
    const std::filesystem::path file = access.resolve(w, uri);
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(file, ec);
    if (ec || size == 0) throw Error(path + ": " + what + ": the file is empty");
    // tinygltf hands a decoder the file's size as an int, and the decoder refuses 1 GiB of pixels anyway.
    if (size >= (uint64_t(1) << 31))
      throw Error(path + ": " + what + ": the file is " + mib(size) + "; rcsplat reads image files under 2 GiB");
    budget.charge(size, what);
    out.files[join_like_tinygltf(out.base_dir, uri)] = {file, size, what};
  });
  // Index accessors without a buffer view: tinygltf wants one, so they get a 4-byte stand-in, read as zeros.
  checks.each("meshes", [&](const json& mesh, const std::string&) {
    for (const json& prim : mesh["primitives"])
      if (prim.contains("indices") && !doc["accessors"][size_t(prim["indices"].get<double>())].contains("bufferView"))
        out.zero_accessors.insert(int(prim["indices"].get<double>()));
  });
  if (!out.zero_accessors.empty()) {
    doc["buffers"].push_back({{"uri", "data:application/octet-stream;base64,AAAAAA=="}, {"byteLength", 4}});
    doc["bufferViews"].push_back({{"buffer", doc["buffers"].size() - 1}, {"byteLength", 4}});
    for (int a : out.zero_accessors) doc["accessors"][size_t(a)]["bufferView"] = doc["bufferViews"].size() - 1;
    rewritten = true;
  }
  if (rewritten) {
    const std::string text_out = doc.dump();
    out.bytes =
        out.binary ? join_glb(bytes, parts, text_out) : std::vector<unsigned char>(text_out.begin(), text_out.end());
  } else {
    out.bytes = std::move(bytes);
  }
  return out;
}

}  // namespace rcsplat
