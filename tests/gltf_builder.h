// Writes small glTF files for the loader and conformance tests.
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "test_support.h"

namespace rcsplat::test {

using nlohmann::json;

// Builds a one-buffer glTF: a quad (4 vertices, 2 triangles) with indices of the chosen component type.
struct GltfBuilder {
  std::vector<uint8_t> bin;
  json doc = {{"asset", {{"version", "2.0"}}}};

  int add_view(const void* data, size_t bytes) {
    while (bin.size() % 4) bin.push_back(0);
    size_t offset = bin.size();
    bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + bytes);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    return int(doc["bufferViews"].size() - 1);
  }
  int add_accessor(int view, int component_type, size_t count, const std::string& type) {
    doc["accessors"].push_back({{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
    return int(doc["accessors"].size() - 1);
  }
  // Writes NAME.gltf and NAME.bin into dir; returns the .gltf path.
  std::string write(const std::string& dir, const std::string& name) {
    doc["buffers"] = json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
    test::write_file(dir + "/" + name + ".bin", std::string(bin.begin(), bin.end()));
    std::string path = dir + "/" + name + ".gltf";
    test::write_file(path, doc.dump(1));
    return path;
  }
};

}  // namespace rcsplat::test
