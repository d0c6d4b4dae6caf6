// The file-access policy for what a scene names (buffers and images): a scene reads only regular files inside its own
// folder and the folders under it, or inside a folder the user adds (--asset-root). Every URI is checked here before
// anything is opened, and a refusal never says whether a file outside those folders exists or how large it is.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rcsplat {

class AssetAccess {
 public:
  // scene_file: the scene as the user named it; its folder (symbolic links resolved) is the first root.
  AssetAccess(const std::string& scene_file, const std::vector<std::string>& extra_roots);

  // The file a relative URI names, resolved and checked: `what` names the object ("buffers[0]") for messages.
  // Throws rcsplat::Error naming the scene, the object, the URI and the rule it breaks.
  std::filesystem::path resolve(const std::string& what, const std::string& uri) const;

  // Reads at most `bytes` bytes from the start of `file` (a path resolve() returned), refusing a file that changed
  // into something else since (a symbolic link or a directory put in its place).
  std::vector<unsigned char> read(const std::filesystem::path& file, uint64_t bytes, const std::string& what) const;

  const std::filesystem::path& scene_folder() const { return roots_.front(); }
  const std::string& scene_file() const { return scene_file_; }

  // A URI's path as glTF means it: percent-escapes decoded (RFC 3986: '+' stays '+').
  static std::string decode_uri(const std::string& uri);

 private:
  bool inside_a_root(const std::filesystem::path& p) const;
  std::string rule() const;

  std::string scene_file_;
  std::vector<std::filesystem::path> roots_;  // canonical
};

}  // namespace rcsplat
