#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <set>

#include "kernels/shared_types.h"
#include "util/error.h"
#include "util/log.h"
#include "util/paths.h"

namespace rcsplat {
namespace {

const std::set<std::string> kSupportedExtensions = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, Scene& scene)
      : path_(path), model_(model), scene_(scene) {}

  void read() {
    for (const std::string& ext : model_.extensionsUsed) {
      if (!kSupportedExtensions.count(ext)) warn("extension " + ext + " is not supported and is ignored");
    }
    for (const std::string& ext : model_.extensionsRequired) {
      if (!kSupportedExtensions.count(ext)) warn("required extension " + ext + " is not supported; the image may differ");
    }
    read_textures();
    read_materials();
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size() ? model_.defaultScene : 0;
      roots = model_.scenes[size_t(s)].nodes;
    } else {
      // No scene: every node that is nobody's child is a root.
      std::vector<bool> is_child(model_.nodes.size(), false);
      for (const auto& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && size_t(c) < is_child.size()) is_child[size_t(c)] = true;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(int(i));
    }
    std::vector<bool> visiting(model_.nodes.size(), false);
    for (int root : roots) visit_node(root, glm::mat4(1.0f), visiting);
    if (scene_.triangle_count() == 0) fail("the scene has no triangles to render");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + what); }
  void warn(const std::string& what) const { log_warning(path_ + ": " + what); }

  // Reads `count` elements of `components` floats from an accessor, after checking it lies inside its buffer.
  // Normalised integer components (allowed for texture coordinates) are converted to [0, 1].
  std::vector<float> read_floats(int accessor_index, int components, const std::string& what) const {
    const tinygltf::Accessor& acc = accessor(accessor_index, what);
    if (tinygltf::GetNumComponentsInType(uint32_t(acc.type)) != components) {
      fail(what + ": accessor " + std::to_string(accessor_index) + " has the wrong type (expected " +
           std::to_string(components) + " components)");
    }
    const unsigned char* data = nullptr;
    size_t stride = 0;
    int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    element_data(acc, accessor_index, components, what, &data, &stride);  // validates before anything is allocated
    std::vector<float> out(acc.count * size_t(components), 0.0f);
    if (!data) return out;  // no buffer view: all zeros, as the specification says
    for (size_t i = 0; i < acc.count; ++i) {
      const unsigned char* e = data + i * stride;
      for (int c = 0; c < components; ++c) {
        const unsigned char* p = e + size_t(c) * size_t(component_size);
        float v;
        switch (acc.componentType) {
          case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&v, p, 4); break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = float(*p) / 255.0f; break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t s;
            std::memcpy(&s, p, 2);
            v = float(s) / 65535.0f;
            break;
          }
          default: fail(what + ": accessor " + std::to_string(accessor_index) + " has an unsupported component type");
        }
        out[i * size_t(components) + size_t(c)] = v;
      }
    }
    return out;
  }

  std::vector<uint32_t> read_indices(int accessor_index, const std::string& what) const {
    const tinygltf::Accessor& acc = accessor(accessor_index, what);
    if (acc.type != TINYGLTF_TYPE_SCALAR) fail(what + ": the index accessor is not SCALAR");
    const unsigned char* data = nullptr;
    size_t stride = 0;
    element_data(acc, accessor_index, 1, what, &data, &stride);
    std::vector<uint32_t> out(acc.count, 0);
    if (!data) return out;
    for (size_t i = 0; i < acc.count; ++i) {
      const unsigned char* p = data + i * stride;
      switch (acc.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = *p; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t s;
          std::memcpy(&s, p, 2);
          out[i] = s;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], p, 4); break;
        default: fail(what + ": indices must be unsigned byte, short or int");
      }
    }
    return out;
  }

  const tinygltf::Accessor& accessor(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(what + ": accessor " + std::to_string(index) + " does not exist");
    return model_.accessors[size_t(index)];
  }

  // Locates an accessor's first element and stride, checking that every element lies inside its buffer.
  void element_data(const tinygltf::Accessor& acc, int index, int components, const std::string& what,
                    const unsigned char** data, size_t* stride) const {
    std::string name = what + ": accessor " + std::to_string(index);
    if (acc.sparse.isSparse) fail(name + " is sparse, which is not supported");
    int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    if (component_size <= 0) fail(name + " has an invalid component type");
    if (acc.bufferView < 0) {
      // No data: all zeros by the specification. Bound the count so that a hostile file cannot demand terabytes.
      if (acc.count > (size_t(1) << 26)) fail(name + " has no buffer view and an implausible count");
      return;
    }
    if (size_t(acc.bufferView) >= model_.bufferViews.size()) fail(name + " refers to a missing buffer view");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(acc.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(name + " refers to a missing buffer");
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
      fail(name + ": buffer view " + std::to_string(acc.bufferView) + " runs past the end of buffer " +
           std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) +
           " bytes): the buffer is truncated or missing");
    }
    size_t element = size_t(component_size) * size_t(components);
    *stride = view.byteStride ? view.byteStride : element;
    if (*stride < element) fail(name + ": byteStride is smaller than one element");
    if (acc.count > 0) {
      size_t last_end = acc.byteOffset + (acc.count - 1) * *stride + element;
      if (acc.byteOffset > view.byteLength || last_end > view.byteLength || (acc.count - 1) > SIZE_MAX / *stride) {
        fail(name + " reads past the end of its buffer view (" + std::to_string(acc.count) + " elements)");
      }
    }
    *data = buffer.data.data() + view.byteOffset + acc.byteOffset;
  }

  static glm::mat4 local_matrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[size_t(i)]);  // column-major, as glTF
      return m;
    }
    glm::mat4 m(1.0f);
    if (node.translation.size() == 3)
      m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4) {
      glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
      m = m * glm::mat4_cast(glm::normalize(q));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
  }

  void visit_node(int index, const glm::mat4& parent, std::vector<bool>& visiting) {
    if (index < 0 || size_t(index) >= model_.nodes.size()) fail("node " + std::to_string(index) + " does not exist");
    if (visiting[size_t(index)]) fail("node " + std::to_string(index) + " is its own ancestor (a cycle)");
    visiting[size_t(index)] = true;
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    glm::mat4 world = parent * local_matrix(node);
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(glm::value_ptr(world)[i])) fail("node " + std::to_string(index) + " has a non-finite transform");
    if (node.mesh >= 0) add_mesh(node.mesh, world);
    if (node.camera >= 0) add_camera(node.camera, world);
    auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext != node.extensions.end() && ext->second.Has("light")) add_light(ext->second.Get("light").GetNumberAsInt(), world);
    for (int child : node.children) visit_node(child, world, visiting);
    visiting[size_t(index)] = false;
  }

  void add_mesh(int mesh_index, const glm::mat4& world) {
    if (size_t(mesh_index) >= model_.meshes.size()) fail("mesh " + std::to_string(mesh_index) + " does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[size_t(mesh_index)];
    glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
    bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;  // a mirroring transform flips the winding
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      std::string what = "mesh " + std::to_string(mesh_index) + " ('" + mesh.name + "') primitive " + std::to_string(p);
      int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES) {
        warn(what + ": primitive mode " + std::to_string(mode) + " is not triangles; rcsplat renders only triangle lists, "
             "so this primitive is skipped");
        continue;
      }
      auto pos_it = prim.attributes.find("POSITION");
      if (pos_it == prim.attributes.end()) fail(what + ": no POSITION attribute");
      std::vector<float> pos = read_floats(pos_it->second, 3, what + " POSITION");
      size_t vertex_count = pos.size() / 3;
      for (size_t i = 0; i < pos.size(); ++i)
        if (!std::isfinite(pos[i])) fail(what + ": vertex " + std::to_string(i / 3) + " has a non-finite position");
      std::vector<float> nrm, uv;
      auto n_it = prim.attributes.find("NORMAL");
      if (n_it != prim.attributes.end()) nrm = read_floats(n_it->second, 3, what + " NORMAL");
      uint32_t material = material_slot(prim.material, what);
      int tex_coord = material_tex_coord(prim.material);
      auto uv_it = prim.attributes.find("TEXCOORD_" + std::to_string(tex_coord));
      if (uv_it != prim.attributes.end()) uv = read_floats(uv_it->second, 2, what + " TEXCOORD");
      if ((!nrm.empty() && nrm.size() != pos.size()) || (!uv.empty() && uv.size() / 2 != vertex_count))
        fail(what + ": attributes have different vertex counts");
      std::vector<uint32_t> idx;
      if (prim.indices >= 0) {
        idx = read_indices(prim.indices, what + " indices");
      } else {
        idx.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) idx[i] = uint32_t(i);
      }
      if (idx.size() % 3 != 0) fail(what + ": index count " + std::to_string(idx.size()) + " is not a multiple of 3");
      for (size_t i = 0; i < idx.size(); ++i) {
        if (idx[i] >= vertex_count) {
          fail(what + ": index " + std::to_string(idx[i]) + " at position " + std::to_string(i) +
               " is out of range (the primitive has " + std::to_string(vertex_count) + " vertices)");
        }
      }
      for (size_t t = 0; t < idx.size(); t += 3) add_triangle(t, idx, pos, nrm, uv, world, normal_matrix, mirrored, material);
    }
  }

  void add_triangle(size_t t, const std::vector<uint32_t>& idx, const std::vector<float>& pos,
                    const std::vector<float>& nrm, const std::vector<float>& uv, const glm::mat4& world,
                    const glm::mat3& normal_matrix, bool mirrored, uint32_t material) {
    uint32_t order[3] = {idx[t], idx[t + 1], idx[t + 2]};
    if (mirrored) std::swap(order[1], order[2]);
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::vec3(world * glm::vec4(pos[3 * order[k]], pos[3 * order[k] + 1], pos[3 * order[k] + 2], 1.0f));
    scene_.add_triangle(p[0], p[1], p[2], material);
    size_t base = scene_.normals.size() - 3;
    glm::vec3 geometric = scene_.normals[base];
    for (int k = 0; k < 3; ++k) {
      if (!nrm.empty()) {
        glm::vec3 n = normal_matrix * glm::vec3(nrm[3 * order[k]], nrm[3 * order[k] + 1], nrm[3 * order[k] + 2]);
        float len = glm::length(n);
        // A zero or non-finite normal falls back to the geometric one rather than poisoning the shading.
        scene_.normals[base + size_t(k)] = (len > 0.0f && std::isfinite(len)) ? n / len : geometric;
      }
      if (!uv.empty()) {
        glm::vec2 u(uv[2 * order[k]], uv[2 * order[k] + 1]);
        scene_.uvs[base + size_t(k)] = (std::isfinite(u.x) && std::isfinite(u.y)) ? u : glm::vec2(0.0f);
      }
    }
  }

  // Scene material slot for a glTF material index; -1 gets the specification's default material (appended once).
  uint32_t material_slot(int index, const std::string& what) {
    if (index >= 0) {
      if (size_t(index) >= model_.materials.size()) fail(what + ": material " + std::to_string(index) + " does not exist");
      return uint32_t(index);
    }
    if (default_material_ < 0) {
      SceneMaterial m;
      m.name = "default";
      default_material_ = int(scene_.materials.size());
      scene_.materials.push_back(m);
    }
    return uint32_t(default_material_);
  }

  int material_tex_coord(int index) const {
    if (index < 0 || size_t(index) >= model_.materials.size()) return 0;
    return model_.materials[size_t(index)].pbrMetallicRoughness.baseColorTexture.texCoord;
  }

  void read_materials() {
    bool warned_metal = false;
    for (const tinygltf::Material& src : model_.materials) {
      SceneMaterial m;
      m.name = src.name;
      const auto& pbr = src.pbrMetallicRoughness;
      for (int i = 0; i < 4 && size_t(i) < pbr.baseColorFactor.size(); ++i) m.base_color[i] = float(pbr.baseColorFactor[size_t(i)]);
      int tex = pbr.baseColorTexture.index;
      if (tex >= 0) {
        if (size_t(tex) >= texture_slots_.size()) fail("material '" + src.name + "': texture " + std::to_string(tex) + " does not exist");
        m.base_color_texture = texture_slots_[size_t(tex)];
      }
      float strength = 1.0f;
      auto ext = src.extensions.find("KHR_materials_emissive_strength");
      if (ext != src.extensions.end() && ext->second.Has("emissiveStrength"))
        strength = float(ext->second.Get("emissiveStrength").GetNumberAsDouble());
      for (int i = 0; i < 3 && size_t(i) < src.emissiveFactor.size(); ++i) m.emission[i] = float(src.emissiveFactor[size_t(i)]) * strength;
      m.double_sided = src.doubleSided;
      for (int i = 0; i < 4; ++i)
        if (!std::isfinite(m.base_color[i]) || m.base_color[i] < 0.0f) fail("material '" + src.name + "': invalid baseColorFactor");
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(m.emission[i]) || m.emission[i] < 0.0f) fail("material '" + src.name + "': invalid emission");
      if (src.emissiveTexture.index >= 0) warn("material '" + src.name + "': emissiveTexture is not supported; emissiveFactor alone is used");
      if (!warned_metal && pbr.metallicFactor > 0.0) {
        warn("material '" + src.name + "' is metallic; rcsplat shades every surface as Lambertian for now");
        warned_metal = true;
      }
      if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty()) warn("material '" + src.name + "': alphaMode " + src.alphaMode + " is ignored (opaque)");
      scene_.materials.push_back(m);
    }
  }

  static int wrap_mode(int gl) {
    if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WRAP_CLAMP;
    if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WRAP_MIRROR;
    return WRAP_REPEAT;
  }

  // glTF textures become scene textures (RGBA8); a texture whose image did not decode maps to -1 with a warning.
  void read_textures() {
    for (size_t t = 0; t < model_.textures.size(); ++t) {
      const tinygltf::Texture& tex = model_.textures[t];
      int slot = -1;
      if (tex.source >= 0 && size_t(tex.source) < model_.images.size()) {
        const tinygltf::Image& img = model_.images[size_t(tex.source)];
        if (img.width > 0 && img.height > 0 && (img.bits == 8 || img.bits == 16) && img.component >= 1 &&
            img.component <= 4 && img.image.size() >= size_t(img.width) * size_t(img.height) * size_t(img.component) * size_t(img.bits / 8)) {
          SceneTexture out;
          out.name = img.uri.empty() ? img.name : img.uri;
          out.width = img.width;
          out.height = img.height;
          size_t texels = size_t(img.width) * size_t(img.height);
          out.rgba.resize(texels * 4);
          int bytes = img.bits / 8;
          for (size_t i = 0; i < texels; ++i) {
            uint8_t c[4] = {0, 0, 0, 255};
            for (int k = 0; k < img.component; ++k) c[k] = img.image[(i * size_t(img.component) + size_t(k)) * size_t(bytes) + size_t(bytes - 1)];
            if (img.component <= 2) c[2] = c[1] = c[0];  // grey (and grey + alpha)
            if (img.component == 2) c[3] = img.image[(i * 2 + 1) * size_t(bytes) + size_t(bytes - 1)];
            std::memcpy(&out.rgba[i * 4], c, 4);
          }
          if (tex.sampler >= 0 && size_t(tex.sampler) < model_.samplers.size()) {
            out.wrap_s = wrap_mode(model_.samplers[size_t(tex.sampler)].wrapS);
            out.wrap_t = wrap_mode(model_.samplers[size_t(tex.sampler)].wrapT);
          }
          slot = int(scene_.textures.size());
          scene_.textures.push_back(std::move(out));
        }
      }
      if (slot < 0) warn("texture " + std::to_string(t) + " has no decodable image; its materials use their factors alone");
      texture_slots_.push_back(slot);
    }
  }

  void add_camera(int index, const glm::mat4& world) {
    if (size_t(index) >= model_.cameras.size()) fail("camera " + std::to_string(index) + " does not exist");
    const tinygltf::Camera& cam = model_.cameras[size_t(index)];
    if (cam.type != "perspective") {
      warn("camera " + std::to_string(index) + " is " + cam.type + "; only perspective cameras are supported, it is skipped");
      return;
    }
    SceneCamera c;
    c.eye = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    glm::vec3 forward = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    c.target = c.eye + forward;
    c.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
    c.yfov = float(cam.perspective.yfov);
    if (!(c.yfov > 0.0f && c.yfov < 3.1f)) fail("camera " + std::to_string(index) + " has an invalid yfov");
    if (cam.perspective.aspectRatio > 0.0) c.aspect = float(cam.perspective.aspectRatio);
    scene_.cameras.push_back(c);
  }

  void add_light(int index, const glm::mat4& world) {
    if (index < 0 || size_t(index) >= model_.lights.size()) fail("light " + std::to_string(index) + " does not exist");
    const tinygltf::Light& src = model_.lights[size_t(index)];
    SceneLight l;
    l.name = src.name;
    if (src.type == "point") l.type = LightType::point;
    else if (src.type == "spot") l.type = LightType::spot;
    else if (src.type == "directional") l.type = LightType::directional;
    else fail("light '" + src.name + "' has unknown type '" + src.type + "'");
    glm::vec3 color(1.0f);
    for (int i = 0; i < 3 && size_t(i) < src.color.size(); ++i) color[i] = float(src.color[size_t(i)]);
    l.intensity = color * float(src.intensity);
    l.range = float(src.range);
    l.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    l.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    l.inner_cone = float(src.spot.innerConeAngle);
    l.outer_cone = float(src.spot.outerConeAngle);
    bool finite = std::isfinite(l.intensity.x) && std::isfinite(l.intensity.y) && std::isfinite(l.intensity.z) &&
                  std::isfinite(l.direction.x) && std::isfinite(l.range);
    if (!finite || l.intensity.x < 0 || l.intensity.y < 0 || l.intensity.z < 0)
      fail("light '" + src.name + "' has an invalid colour, intensity or orientation");
    scene_.lights.push_back(l);
  }

  std::string path_;
  const tinygltf::Model& model_;
  Scene& scene_;
  std::vector<int> texture_slots_;
  int default_material_ = -1;
};

}  // namespace

Scene load_gltf(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path + ": no such file");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  std::string ext = lower_extension(path);
  bool ok;
  try {
    ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                       : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  } catch (const std::exception& e) {
    throw Error(path + ": cannot be parsed: " + e.what());
  }
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    throw Error(path + ": cannot be loaded: " + (err.empty() ? "unknown error" : err));
  }
  if (!warn.empty()) {
    while (!warn.empty() && warn.back() == '\n') warn.pop_back();
    log_warning(path + ": " + warn);
  }
  Scene scene;
  scene.source = path;
  GltfReader(path, model, scene).read();
  return scene;
}

}  // namespace rcsplat
