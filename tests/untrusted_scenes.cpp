#include "untrusted_scenes.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <tuple>

namespace rcsplat::test {
namespace {

using nlohmann::json;

template <typename T>
void append(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// A unit quad facing +z, seen from the default camera, lit by the default light: 48 bytes of positions, 12 of
// 16-bit indices. Its buffer is `uri` (or, for a GLB, the BIN chunk when uri is empty).
json quad(const std::string& uri, std::string* bin) {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  bin->clear();
  for (float p : positions) append(*bin, p);
  for (uint16_t i : indices) append(*bin, i);
  json buffer = {{"byteLength", bin->size()}};
  if (!uri.empty()) buffer["uri"] = uri;
  return {
      {"asset", {{"version", "2.0"}}},
      {"buffers", json::array({buffer})},
      {"bufferViews", json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                                   {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}})},
      {"accessors", json::array({{{"bufferView", 0},
                                  {"componentType", 5126},
                                  {"count", 4},
                                  {"type", "VEC3"},
                                  {"min", {0, 0, 0}},
                                  {"max", {1, 1, 0}}},
                                 {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}})},
      {"meshes", json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}})}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"scene", 0}};
}

// The quad with its buffer in scene/quad.bin.
UntrustedCase quad_case(const std::string& name, const std::function<void(json&)>& edit = {}) {
  UntrustedCase c;
  c.name = name;
  std::string bin;
  json doc = quad("quad.bin", &bin);
  if (edit) edit(doc);
  c.files["scene/quad.bin"] = bin;
  c.files["scene/scene.gltf"] = doc.dump();
  c.files["secret.bin"] = std::string(1234567, 'S');  // beside the scene's folder: never to be read, nor its size told
  return c;
}

std::string glb(const json& doc, const std::string& bin) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  std::string padded = bin;
  while (padded.size() % 4) padded += '\0';
  std::string out;
  append(out, uint32_t(0x46546C67));
  append(out, uint32_t(2));
  append(out, uint32_t(12 + 8 + text.size() + (padded.empty() ? 0 : 8 + padded.size())));
  append(out, uint32_t(text.size()));
  append(out, uint32_t(0x4E4F534A));
  out += text;
  if (!padded.empty()) {
    append(out, uint32_t(padded.size()));
    append(out, uint32_t(0x004E4942));
    out += padded;
  }
  return out;
}

uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A PNG that is only a signature and a header claiming width x height: a decoder would allocate before it found
// the data missing.
std::string png_header_only(uint32_t width, uint32_t height) {
  auto be = [](uint32_t v) {
    std::string s(4, '\0');
    for (int k = 0; k < 4; ++k) s[size_t(k)] = char((v >> (24 - 8 * k)) & 0xff);
    return s;
  };
  std::string chunk = "IHDR" + be(width) + be(height) + std::string("\x08\x06\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + be(13) + chunk + be(crc32(chunk));
}

const char* const kTwoPixelPng =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAIAAAB7QOjdAAAAEElEQVR4nGNgYPj/n4GBAQAJ/AH/"
    "WNvyFwAAAABJRU5ErkJggg==";

void textured(json& doc, const json& image) {
  doc["images"] = json::array({image});
  doc["textures"] = json::array({{{"source", 0}}});
  doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  doc["meshes"][0]["primitives"][0]["material"] = 0;
}

}  // namespace

std::vector<UntrustedCase> untrusted_cases() {
  std::vector<UntrustedCase> cases;
  const std::string leaves = "the path leaves the scene's folder";
  const std::string secret_size = "1234567";

  // ---- 1. Files outside the scene's folder ----
  {
    UntrustedCase c = quad_case("BufferWithDotDot", [](json& d) { d["buffers"][0]["uri"] = "../secret.bin"; });
    c.key_words = {"buffers[0] '../secret.bin'", leaves, "--asset-root"};
    c.absent_words = {secret_size};
    cases.push_back(c);
  }
  {
    UntrustedCase c =
        quad_case("BufferWithPercentEncodedDotDot", [](json& d) { d["buffers"][0]["uri"] = "%2e%2e/secret.bin"; });
    c.key_words = {"buffers[0] '%2e%2e/secret.bin'", leaves};
    c.absent_words = {secret_size};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("BufferAtAnAbsolutePath", [](json& d) { d["buffers"][0]["uri"] = "/etc/passwd"; });
    c.key_words = {"buffers[0] '/etc/passwd'", "absolute paths are not read"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("BufferAsFileUri", [](json& d) { d["buffers"][0]["uri"] = "file:///etc/passwd"; });
    c.key_words = {"buffers[0] 'file:///etc/passwd'", "file: URIs are not read"};
    cases.push_back(c);
  }
  {
    UntrustedCase c =
        quad_case("BufferOverTheNetwork", [](json& d) { d["buffers"][0]["uri"] = "https://example.com/q.bin"; });
    c.key_words = {"buffers[0]", "the URI scheme 'https:' is not read"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("ImageWithDotDot", [](json& d) { textured(d, {{"uri", "../secret.png"}}); });
    c.files["secret.png"] = png_header_only(2, 2);
    c.key_words = {"images[0] '../secret.png'", leaves};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("SymbolicLinkLeadingOut", [](json& d) { d["buffers"][0]["uri"] = "inside.bin"; });
    c.symlinks["scene/inside.bin"] = "../secret.bin";
    c.key_words = {"buffers[0] 'inside.bin'", "a symbolic link leads out of the scene's folder"};
    c.absent_words = {secret_size};
    cases.push_back(c);
  }
  {  // the same refusal whether the link's target exists or not: nothing tells which
    UntrustedCase c =
        quad_case("SymbolicLinkLeadingOutToNothing", [](json& d) { d["buffers"][0]["uri"] = "inside.bin"; });
    c.symlinks["scene/inside.bin"] = "../no-such-file.bin";
    c.key_words = {"buffers[0] 'inside.bin'", "a symbolic link leads out of the scene's folder"};
    cases.push_back(c);
  }
  {  // tinygltf alone would find it relative to the working folder after missing it beside the scene
    UntrustedCase c =
        quad_case("BufferOnlyInTheWorkingFolder", [](json& d) { d["buffers"][0]["uri"] = "elsewhere.bin"; });
    c.working_folder_file = "elsewhere.bin";
    c.key_words = {"buffers[0] 'elsewhere.bin'", "no such file in the scene's folder"};
    cases.push_back(c);
  }
  {  // a user who trusts the scene widens the rule
    UntrustedCase c =
        quad_case("AssetRootWidensTheRule", [](json& d) { d["buffers"][0]["uri"] = "../shared/quad.bin"; });
    c.files["shared/quad.bin"] = c.files["scene/quad.bin"];
    c.args = {"--asset-root", "{case}/shared"};
    c.renders = true;
    cases.push_back(c);
  }
  {
    UntrustedCase c =
        quad_case("AssetRootIsNoWiderThanItSays", [](json& d) { d["buffers"][0]["uri"] = "../secret.bin"; });
    c.files["shared/quad.bin"] = c.files["scene/quad.bin"];
    c.args = {"--asset-root", "{case}/shared"};
    c.key_words = {"buffers[0] '../secret.bin'", leaves, "inside --asset-root"};
    cases.push_back(c);
  }

  // ---- 2. Bounded work ----
  {  // 40 nodes, each listing the next twice: 2^40 paths to a walk that follows every one
    UntrustedCase c = quad_case("ExponentialNodeGraph", [](json& d) {
      json nodes = json::array();
      for (int i = 0; i < 40; ++i) nodes.push_back({{"children", {i + 1, i + 1}}});
      nodes.push_back({{"mesh", 0}});
      d["nodes"] = nodes;
    });
    c.key_words = {"nodes[0]", "lists nodes[1] twice as a child"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("NodeWithTwoParents", [](json& d) {
      d["nodes"] = json::array({{{"children", {2}}}, {{"children", {2}}}, {{"mesh", 0}}});
      d["scenes"][0]["nodes"] = {0, 1};
    });
    c.key_words = {"nodes[2]", "has two parents, nodes[0] and nodes[1]"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("NodeCycleWithoutAScene", [](json& d) {
      d["nodes"] = json::array({{{"children", {1}}, {"mesh", 0}}, {{"children", {0}}}});
      d.erase("scenes");
      d.erase("scene");
    });
    c.key_words = {"is its own ancestor", "nodes[0]"};
    cases.push_back(c);
  }
  {  // valid glTF, 100,000 deep: the walk needs no call stack
    UntrustedCase c = quad_case("ChainOfOneHundredThousandNodes", [](json& d) {
      json nodes = json::array();
      for (int i = 0; i < 100000; ++i) nodes.push_back({{"children", {i + 1}}});
      nodes.push_back({{"mesh", 0}});
      d["nodes"] = nodes;
    });
    c.renders = true;
    cases.push_back(c);
  }
  {  // tinygltf copies "extras" recursively: 100,000 nested arrays overflowed its stack
    UntrustedCase c = quad_case("ExtrasNestedOneHundredThousandDeep");
    std::string& text = c.files["scene/scene.gltf"];
    text.insert(text.size() - 1, ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']'));
    c.key_words = {"the JSON nests arrays and objects more than 128 deep (at byte"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("InstancesBeyondTheTriangleLimit", [](json& d) {
      json nodes = json::array(), roots = json::array();
      for (int i = 0; i < 600; ++i) nodes.push_back({{"mesh", 0}, {"translation", {i, 0, 0}}}), roots.push_back(i);
      d["nodes"] = nodes;
      d["scenes"][0]["nodes"] = roots;
    });
    c.args = {"--max-triangles", "1000"};
    c.key_words = {"places 1200 triangles, more than the limit of 1000 (--max-triangles)", "meshes[0]", "600 node(s)"};
    cases.push_back(c);
  }
  {  // 100 M zero indices without a buffer view: 33 M triangles from a few hundred bytes
    UntrustedCase c = quad_case("IndicesWithoutDataBeyondTheLimit", [](json& d) {
      d["accessors"].push_back({{"componentType", 5125}, {"count", 100000000}, {"type", "SCALAR"}});
      d["meshes"][0]["primitives"][0]["indices"] = 2;
    });
    c.key_words = {"places 33333333 triangles, more than the limit of 16777216"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }

  {  // valid glTF that tinygltf alone refuses: an index accessor without a buffer view reads as zeros
    UntrustedCase c = quad_case("IndicesWithoutDataAreZeros", [](json& d) {
      d["accessors"].push_back({{"componentType", 5125}, {"count", 3}, {"type", "SCALAR"}});
      d["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 2}});
    });
    c.renders = true;
    cases.push_back(c);
  }

  // ---- 3. Bounded memory ----
  {  // 2^26 zero positions without a buffer view and no indices: 22 M triangles
    UntrustedCase c = quad_case("PositionsWithoutDataBeyondTheLimit", [](json& d) {
      d["accessors"][0] = {{"componentType", 5126}, {"count", 1 << 26}, {"type", "VEC3"}};
      d["meshes"][0]["primitives"][0].erase("indices");
    });
    c.key_words = {"places 22369621 triangles, more than the limit"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {  // 2^26 positions without data, of which the indices read four (set by sparse substitution): valid, and small
    UntrustedCase c = quad_case("PositionsWithoutDataReadOnlyAsFarAsIndexed", [](json& d) {
      d["accessors"][0] = {
          {"componentType", 5126},
          {"count", 1 << 26},
          {"type", "VEC3"},
          {"sparse",
           {{"count", 4}, {"indices", {{"bufferView", 2}, {"componentType", 5123}}}, {"values", {{"bufferView", 0}}}}}};
      d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 8}});
      d["buffers"][0]["byteLength"] = 68;
    });
    for (uint16_t i : {0, 1, 2, 3}) append(c.files["scene/quad.bin"], i);  // the substitutions: vertices 0..3
    c.renders = true;
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {  // one joint, 2^26 inverse bind matrices without data: only the joint's matrix is read
    UntrustedCase c = quad_case("InverseBindMatricesReadOnlyForTheJoints", [](json& d) {
      d["accessors"].push_back({{"componentType", 5126}, {"count", 1 << 26}, {"type", "MAT4"}});
      d["accessors"].push_back({{"componentType", 5121}, {"count", 4}, {"type", "VEC4"}});  // JOINTS_0: all joint 0
      d["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
      d["skins"] = json::array({{{"joints", {1}}, {"inverseBindMatrices", 2}}});
      d["nodes"] = json::array({{{"mesh", 0}, {"skin", 0}}, json::object()});
      d["scenes"][0]["nodes"] = {0, 1};
      d["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = 3;
      d["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = 4;
    });
    std::string& bin = c.files["scene/quad.bin"];
    for (int v = 0; v < 4; ++v)
      for (float w : {1.0f, 0.0f, 0.0f, 0.0f}) append(bin, w);
    json doc = json::parse(c.files["scene/scene.gltf"]);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 64}});
    doc["buffers"][0]["byteLength"] = bin.size();
    c.files["scene/scene.gltf"] = doc.dump();
    // An identity bind matrix of zeros poses every vertex at the origin: the image is black, the load is the point.
    c.renders = true;
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("BuffersBeyondTheHostBudget");
    c.files["scene/quad.bin"] += std::string(20 << 20, '\0');
    json doc = json::parse(c.files["scene/scene.gltf"]);
    doc["buffers"][0]["byteLength"] = c.files["scene/quad.bin"].size();
    c.files["scene/scene.gltf"] = doc.dump();
    c.args = {"--max-host-memory", "0.01"};
    c.key_words = {"buffers[0] 'quad.bin'", "of host memory, beyond the scene's budget of 10.2 MiB",
                   "--max-host-memory"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {  // a PNG header claiming 60000 x 60000 pixels (14 GB decoded) and no data
    UntrustedCase c = quad_case("ImageHeaderBeyondTheSideLimit", [](json& d) { textured(d, {{"uri", "huge.png"}}); });
    c.files["scene/huge.png"] = png_header_only(60000, 60000);
    c.key_words = {"images[0] 'huge.png'", "is 60000 x 60000 pixels; rcsplat reads textures of at most 16384"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("ImageHeaderBeyondTheHostBudget", [](json& d) { textured(d, {{"uri", "big.png"}}); });
    c.files["scene/big.png"] = png_header_only(16000, 16000);
    c.args = {"--max-host-memory", "0.5"};
    c.key_words = {"images[0] 'big.png' (decoded) needs", "beyond the scene's budget", "--max-host-memory"};
    c.memory_ceiling_mib = 600;
    cases.push_back(c);
  }

  // ---- 4. Messages that name the file, the object and the defect ----
  {
    UntrustedCase c;
    c.name = "EmptyGlb";
    c.scene = "scene/empty.glb";
    c.files[c.scene] = "";
    c.key_words = {"empty.glb", "the file is empty"};
    cases.push_back(c);
  }
  std::string bin;
  const std::string whole_glb = glb(quad("", &bin), bin);
  for (const auto& [name, cut, words] :
       {std::tuple<const char*, size_t, const char*>{"GlbCutInItsHeader", 10, "inside the 12-byte GLB header"},
        {"GlbCutInItsJsonChunk", 100, "the JSON chunk says it holds"},
        {"GlbCutInItsBinChunk", whole_glb.size() - 8, "the BIN chunk says it holds"}}) {
    UntrustedCase c;
    c.name = name;
    c.scene = "scene/cut.glb";
    std::string cut_glb = whole_glb.substr(0, cut);
    // The header's length says what the file held before the cut: a truncated file, not an inconsistent one.
    c.files[c.scene] = cut_glb;
    c.key_words = {"cut.glb", words};
    if (cut > 12)
      c.key_words.push_back("the header says the file holds " + std::to_string(whole_glb.size()) +
                            " bytes: it is truncated");
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("SkinThatIsAnEmptyObject", [](json& d) {
      d["skins"] = json::array({json::object()});
      d["nodes"][0]["skin"] = 0;
    });
    c.key_words = {"skins[0]", "\"joints\" is required"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("TextureFileThatIsNotAnImage", [](json& d) { textured(d, {{"uri", "wood.png"}}); });
    c.files["scene/wood.png"] = "this is not a picture";
    c.key_words = {"images[0] 'wood.png'", "not an image rcsplat reads"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("AccessorIndexOutOfRange",
                                [](json& d) { d["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 7; });
    c.key_words = {"meshes[0].primitives[0].attributes.NORMAL", "is 7, but the file has 2 accessors"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("AccessorPastItsBufferView", [](json& d) { d["accessors"][0]["count"] = 5; });
    c.key_words = {"accessors[0] (meshes[0].primitives[0].POSITION)", "run past the end of bufferViews[0]"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("DataUriThatIsNotBase64", [](json& d) {
      d["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA!AAA";
    });
    c.key_words = {"buffers[0]", "not base64 at character 41"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("NotJson");
    c.files["scene/scene.gltf"] = "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [";
    c.key_words = {"scene.gltf: is not valid JSON", "unexpected end of input"};
    cases.push_back(c);
  }
  {  // a name is a stranger's text: a terminal escape in it is printed as \x1b, never sent to the terminal
    UntrustedCase c = quad_case("NameWithATerminalEscape", [](json& d) {
      d["materials"] =
          json::array({{{"name", "clear\x1b[2Jscreen"}, {"pbrMetallicRoughness", {{"metallicFactor", 2.0}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
    });
    c.key_words = {"materials[0] 'clear\\x1b[2Jscreen': metallicFactor"};
    c.absent_words = {"\x1b"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("MissingBufferFile", [](json& d) { d["buffers"][0]["uri"] = "gone.bin"; });
    c.key_words = {"buffers[0] 'gone.bin'", "no such file in the scene's folder"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("TruncatedBufferFile");
    c.files["scene/quad.bin"].resize(40);
    c.key_words = {"buffers[0] 'quad.bin'", "byteLength says 60 bytes, but the file holds 40"};
    cases.push_back(c);
  }

  // ---- 5. Valid files render ----
  {
    UntrustedCase c = quad_case("TextureWithoutAnImage", [](json& d) {
      textured(d, {{"uri", kTwoPixelPng}});
      d["textures"][0].erase("source");
    });
    c.renders = true;
    c.key_words = {"textures[0] has no image", "untextured"};
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("UnusedBufferWithoutUri", [](json& d) {
      d["buffers"].push_back({{"byteLength", 64}});
    });
    c.renders = true;
    cases.push_back(c);
  }
  {  // the same in a GLB, whose JSON chunk rcsplat writes again for tinygltf
    UntrustedCase c;
    c.name = "GlbWithAnUnusedBufferWithoutUri";
    c.scene = "scene/quad.glb";
    std::string bin;
    json doc = quad("", &bin);
    doc["buffers"].push_back({{"byteLength", 64}});
    c.files[c.scene] = glb(doc, bin);
    c.renders = true;
    cases.push_back(c);
  }
  {
    UntrustedCase c = quad_case("TexturedFromTheScenesFolder", [](json& d) {
      textured(d, {{"uri", "textures/two%20pixels.png"}});
    });
    c.files["scene/textures/two pixels.png"] = "";  // filled below from the data URI's bytes
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const std::string b64 = std::string(kTwoPixelPng).substr(std::strlen("data:image/png;base64,"));
    std::string png;
    uint32_t acc = 0;
    int bits = 0;
    for (char ch : b64) {
      if (ch == '=') break;
      acc = (acc << 6) | uint32_t(std::strchr(alphabet, ch) - alphabet);
      bits += 6;
      if (bits >= 8) png += char((acc >> (bits -= 8)) & 0xff);
    }
    c.files["scene/textures/two pixels.png"] = png;
    c.renders = true;
    cases.push_back(c);
  }
  // Normal maps, textured emission, blending and WebP (issue 61): the quad with texture coordinates (bytes 60..91)
  // and one material using them all.
  auto mapped_quad = [](json& d, std::string& bin) {
    for (float f : {0.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f}) append(bin, f);
    d["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 32}});
    d["buffers"][0]["byteLength"] = bin.size();
    d["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
    d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
    d["images"] = json::array({{{"uri", kTwoPixelPng}}});
    d["textures"] = json::array({{{"source", 0}}});
    d["materials"] = json::array({{{"normalTexture", {{"index", 0}, {"scale", 3.0}}},
                                   {"emissiveTexture", {{"index", 0}}},
                                   {"emissiveFactor", {1.0, 0.5, 0.25}},
                                   {"alphaMode", "BLEND"},
                                   {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 1.0, 1.0, 0.5}}}}}});
    d["meshes"][0]["primitives"][0]["material"] = 0;
  };
  {  // valid: tangents made from the texture coordinates, every feature on
    UntrustedCase c = quad_case("NormalMappedBlendedEmitterRenders");
    json d = json::parse(c.files["scene/scene.gltf"]);
    mapped_quad(d, c.files["scene/quad.bin"]);
    c.files["scene/scene.gltf"] = d.dump();
    c.renders = true;
    cases.push_back(c);
  }
  {  // a TANGENT accessor that runs past its buffer view
    UntrustedCase c = quad_case("TangentsPastTheirView");
    json d = json::parse(c.files["scene/scene.gltf"]);
    mapped_quad(d, c.files["scene/quad.bin"]);
    d["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
    d["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 3;
    c.files["scene/scene.gltf"] = d.dump();
    c.key_words = {"accessors[3]"};
    cases.push_back(c);
  }
  {  // EXT_texture_webp naming an image the file does not have
    UntrustedCase c = quad_case("WebPSourceOutOfRange");
    json d = json::parse(c.files["scene/scene.gltf"]);
    mapped_quad(d, c.files["scene/quad.bin"]);
    d["textures"][0]["extensions"] = {{"EXT_texture_webp", {{"source", 7}}}};
    c.files["scene/scene.gltf"] = d.dump();
    c.key_words = {"textures[0]", "EXT_texture_webp"};
    cases.push_back(c);
  }
  {  // glass whose volume names a thickness texture on a primitive without texture coordinates: rendered, the texture
     // named as not read (rays cross the mesh's own volume)
    UntrustedCase c = quad_case("GlassThicknessTextureWithoutCoordinates", [](json& d) {
      d["materials"] = json::array({{{"pbrMetallicRoughness", {{"roughnessFactor", 0.0}}},
                                     {"extensions",
                                      {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                       {"KHR_materials_volume",
                                        {{"thicknessFactor", 0.1}, {"thicknessTexture", {{"index", 0}}}}}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
      d["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
    });
    c.args = {"--sky", "0.3,0.4,0.6"};
    c.renders = true;
    c.key_words = {"thicknessTexture"};
    cases.push_back(c);
  }
  {  // an index of refraction below 1
    UntrustedCase c = quad_case("GlassIorBelowOne", [](json& d) {
      d["materials"] = json::array({{{"name", "lens"},
                                     {"extensions",
                                      {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                       {"KHR_materials_ior", {{"ior", 0.5}}}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
    });
    c.key_words = {"materials[0] 'lens'", "ior"};
    cases.push_back(c);
  }
  {  // attenuation at distance 0: an infinite coefficient
    UntrustedCase c = quad_case("GlassAttenuationDistanceZero", [](json& d) {
      d["materials"] = json::array({{{"extensions",
                                      {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                       {"KHR_materials_volume",
                                        {{"thicknessFactor", 1.0}, {"attenuationDistance", 0.0},
                                         {"attenuationColor", {0.5, 0.5, 0.5}}}}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
    });
    c.key_words = {"materials[0]", "attenuationDistance"};
    cases.push_back(c);
  }
  {  // a clearcoat whose normal texture names no texture of the file
    UntrustedCase c = quad_case("ClearcoatNormalTextureMissing", [](json& d) {
      d["materials"] = json::array({{{"extensions",
                                      {{"KHR_materials_clearcoat",
                                        {{"clearcoatFactor", 1.0}, {"clearcoatNormalTexture", {{"index", 0}}}}}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
      d["extensionsUsed"] = {"KHR_materials_clearcoat"};
    });
    c.key_words = {"materials[0]", "clearcoatNormalTexture"};
    cases.push_back(c);
  }
  {  // a sheen colour above 1
    UntrustedCase c = quad_case("SheenColourAboveOne", [](json& d) {
      d["materials"] = json::array({{{"name", "velvet"},
                                     {"extensions", {{"KHR_materials_sheen", {{"sheenColorFactor", {1.0, 7.0, 1.0}}}}}}}});
      d["meshes"][0]["primitives"][0]["material"] = 0;
    });
    c.key_words = {"materials[0] 'velvet'", "sheenColorFactor"};
    cases.push_back(c);
  }
  return cases;
}

void write_untrusted_case(const UntrustedCase& c, const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  for (const auto& [name, bytes] : c.files) {
    const std::filesystem::path path = folder / name;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }
  for (const auto& [link, target] : c.symlinks) {
    const std::filesystem::path path = folder / link;
    std::filesystem::create_directories(path.parent_path());
    std::error_code ec;
    std::filesystem::remove(path, ec);
    std::filesystem::create_symlink(target, path);
  }
}

}  // namespace rcsplat::test
