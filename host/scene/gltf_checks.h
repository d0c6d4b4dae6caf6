// What rcsplat checks of a glTF file before tinygltf parses it (docs/SECURITY.md): the GLB container, the JSON, the
// objects' required properties and references, the node graph (one parent each, no cycles), and every buffer and
// image URI under the file-access policy (scene/asset_access.h), with the bytes each may take counted against the
// host budget. A refusal names the file, the object ("buffers[1] 'mesh.bin'", "nodes[12]") and the defect.
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "scene/asset_access.h"
#include "scene/scene_limits.h"

namespace rcsplat {

// Counts the host bytes a scene takes against SceneLimits::host_budget(), refusing before the allocation.
class HostBudget {
 public:
  HostBudget(const std::string& scene_file, const SceneLimits& limits);
  void charge(uint64_t bytes, const std::string& what);
  // Refuses as charge() would, without taking the bytes: for arrays freed again before more is charged.
  void check_fits(uint64_t bytes, const std::string& what) const;
  uint64_t used() const { return used_; }
  uint64_t budget() const { return budget_; }

 private:
  std::string scene_file_;
  uint64_t budget_ = 0, used_ = 0;
};

struct CheckedGltf {
  bool binary = false;
  std::vector<unsigned char> bytes;  // what tinygltf parses: the JSON text, or the whole GLB
  std::string base_dir;              // the scene's folder, as tinygltf joins it to URIs
  struct ExternalFile {
    std::filesystem::path file;  // resolved and checked by AssetAccess
    uint64_t bytes;              // bytes to read from its start (a buffer's byteLength, an image's size)
    std::string what;            // "buffers[0] 'sponza.bin'"
  };
  // The external files tinygltf may open, keyed by the path it asks for: its base directory joined to the URI as
  // tinygltf 2.7 decodes it. Any other path is refused (this is what stops its retry relative to the working folder).
  std::map<std::string, ExternalFile> files;
  // Index accessors without a buffer view (zeros, valid glTF) that tinygltf 2.7 would refuse: each is pointed at a
  // 4-byte stand-in view for the parse, and read as zeros (gltf_loader.cpp).
  std::set<int> zero_accessors;
};

CheckedGltf check_gltf(const AssetAccess& access, const SceneLimits& limits, HostBudget& budget);

}  // namespace rcsplat
