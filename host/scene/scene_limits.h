// What a scene file may make rcsplat read, allocate and do: every scene is treated as written by a stranger
// (docs/SECURITY.md). The defaults suit any scene rcsplat renders well; a farm tightens them, a user who trusts a scene
// widens them (--asset-root, --max-triangles, --max-host-memory).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rcsplat {

struct SceneLimits {
  // Folders a scene's relative URIs may lead into besides its own folder (the one holding the file, symbolic links
  // resolved): `..` and symbolic links may reach these, nothing else. Absolute paths and file:// URIs are never read.
  std::vector<std::string> asset_roots;
  // Triangles after instancing (a mesh counts once per node that places it), checked before any is made.
  uint64_t max_triangles = uint64_t(1) << 24;
  // Host memory the scene may take: its file, buffers and images as read, the decoded textures and the triangles with
  // everything a frame derives from them (kHostBytesPerTriangle). 0: three quarters of this machine's memory.
  uint64_t host_memory_bytes = 0;
  // The glTF JSON (a .gltf file, or a GLB's JSON chunk): metadata; geometry belongs in buffers.
  uint64_t max_json_bytes = uint64_t(256) << 20;
  // Either side of a texture, in pixels.
  int max_texture_side = 16384;
  // Device memory a frame may hold at once (scene, BVH and frame buffers). 0: all the device has.
  uint64_t device_memory_bytes = 0;

  uint64_t host_budget() const;  // host_memory_bytes, or its default
};

// Host bytes a triangle costs a frame: the loaded scene (positions, normals, uvs, colours: 136 B), the packed
// triangles (128 B), the BVH build and its flattened nodes, and on PoCL the device's copies, which live in host memory
// too. Measured as the slope of `rcsplat render` peak resident memory between 320,000 and 1,280,000 triangles
// (docs/SECURITY.md): 713 B with --gi none, 800 B with the defaults.
constexpr uint64_t kHostBytesPerTriangle = 800;

}  // namespace rcsplat
