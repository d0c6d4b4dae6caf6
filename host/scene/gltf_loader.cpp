#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <algorithm>
#include <optional>
#include <set>

#include <stb/stb_image.h>
#include <webp/decode.h>

#include "kernels/shared_types.h"
#include "scene/gltf_checks.h"
#include "scene/tangents.h"
#include "util/error.h"
#include "util/log.h"
#include "util/paths.h"

namespace rcsplat {
namespace {

const std::set<std::string> kSupportedExtensions = {"KHR_lights_punctual", "KHR_materials_emissive_strength",
                                                    "KHR_materials_specular", "KHR_texture_transform",
                                                    "EXT_texture_webp", "KHR_materials_transmission",
                                                    "KHR_materials_ior", "KHR_materials_volume",
                                                    "KHR_materials_clearcoat", "KHR_materials_sheen"};

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, Scene& scene, const SceneLimits& limits,
             HostBudget& budget, const std::set<int>& zero_accessors, const ScenePose& pose)
      : path_(path),
        model_(model),
        scene_(scene),
        limits_(limits),
        budget_(budget),
        zero_accessors_(zero_accessors),
        pose_(pose) {}

  void read() {
    for (const std::string& ext : model_.extensionsUsed) {
      if (kSupportedExtensions.count(ext)) continue;
      bool required = std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), ext) !=
                      model_.extensionsRequired.end();
      note_unsupported("extension " + ext + (required ? " (required)" : ""),
                       ext.rfind("KHR_materials_", 0) == 0 ? "ignored: surfaces are opaque, shaded with the metallic-roughness BRDF"
                                                           : "ignored; the image may differ from the author's");
    }
    if (!model_.animations.empty() && pose_.animation < 0 && !pose_.played_by_caller)
      note_unsupported(std::to_string(model_.animations.size()) + " animation(s)",
                       "render draws the nodes' rest transforms and weights; `rcsplat animate` plays them (meshes "
                       "and lights moved rigidly with one cache; skins with --cache-per-frame)");
    read_textures();
    read_materials();
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      int s = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size() ? model_.defaultScene : 0;
      roots = model_.scenes[size_t(s)].nodes;
    } else {
      // No scene: every node that is nobody's child is a root (check_gltf refused cycles and second parents).
      std::vector<bool> is_child(model_.nodes.size(), false);
      for (const auto& n : model_.nodes)
        for (int c : n.children) is_child[size_t(c)] = true;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(int(i));
    }
    check_instanced_triangles(roots);
    pose_nodes();
    // Depth first with a stack of its own: a chain of 100,000 nodes is as deep as the heap allows, not the call stack.
    // The graph is a forest (check_gltf), so each node is visited once.
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, glm::mat4(1.0f));
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      const glm::mat4 world = visit_node(index, parent);
      const std::vector<int>& children = model_.nodes[size_t(index)].children;
      for (auto c = children.rbegin(); c != children.rend(); ++c) stack.emplace_back(*c, world);
    }
    if (scene_.triangle_count() == 0) fail("the scene has no triangles to render");
    read_animations();
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + what); }
  // A JSON number used as an index, or -1 when it is none (tinygltf's GetNumberAsInt converts 1e23 to int: undefined
  // behaviour, found by fuzzing).
  static int index_value(const tinygltf::Value& v) {
    if (!v.IsNumber()) return -1;
    double d = v.GetNumberAsDouble();
    return d >= 0.0 && d <= double(std::numeric_limits<int>::max()) && d == std::floor(d) ? int(d) : -1;
  }
  void warn(const std::string& what) const { log_warning(path_ + ": " + what); }
  // A feature rcsplat does not simulate: named once per scene, in a warning and in the render summary.
  void note_unsupported(const std::string& feature, const std::string& instead) {
    std::string line = feature + ": " + instead;
    if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), line) != scene_.unsupported.end()) return;
    scene_.unsupported.push_back(line);
    warn("not simulated: " + line);
  }

  // "accessors[7] (meshes[0].primitives[1].POSITION)": an accessor and the use it is read for, for messages.
  static std::string accessor_name(int index, const std::string& use) {
    return "accessors[" + std::to_string(index) + "] (" + use + ")";
  }

  // Reads the first `needed` elements (all, when fewer) of an accessor, `components` values each, as floats: float
  // components as they are, integer components normalised to [0, 1] (or [-1, 1] when signed) unless `integers`, which
  // keeps their values (JOINTS_0). A sparse accessor's substitutions are applied. Every read is checked against its
  // buffer first, and the floats made are charged to the host budget before they are allocated: an accessor without
  // a buffer view (zeros, with sparse substitutions) is as large as its reader needs, not as its count says.
  std::vector<float> read_floats(int accessor_index, int components, const std::string& use, bool integers = false,
                                 size_t needed = SIZE_MAX) const {
    const tinygltf::Accessor& acc = accessor(accessor_index, use);
    const std::string name = accessor_name(accessor_index, use);
    if (tinygltf::GetNumComponentsInType(uint32_t(acc.type)) != components)
      fail(name + " has the wrong type (" + std::to_string(components) + " components expected)");
    const unsigned char* data = nullptr;
    size_t stride = 0;
    element_data(acc, accessor_index, components, use, &data, &stride);  // validates before anything is allocated
    const size_t count = std::min(acc.count, needed);
    charge_transient(uint64_t(count) * uint64_t(components) * sizeof(float), name);
    std::vector<float> out(count * size_t(components), 0.0f);
    int size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    auto read_element = [&](const unsigned char* e, size_t slot) {
      for (int c = 0; c < components; ++c)
        out[slot * size_t(components) + size_t(c)] =
            component(acc.componentType, e + size_t(c) * size_t(size), integers, name);
    };
    if (data)  // no buffer view: all zeros, as the specification says (then sparse substitutions, if any)
      for (size_t i = 0; i < count; ++i) read_element(data + i * stride, i);
    if (acc.sparse.isSparse) {
      const std::string sparse = name + " sparse";
      size_t substitutions = size_t(std::max(acc.sparse.count, 0));
      int index_size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.sparse.indices.componentType));
      if (index_size <= 0 || acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
          acc.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
        fail(sparse + ": indices must be unsigned byte, short or int");
      const unsigned char* indices = view_range(acc.sparse.indices.bufferView, size_t(acc.sparse.indices.byteOffset),
                                                substitutions * size_t(index_size), sparse + " indices");
      const unsigned char* values = view_range(acc.sparse.values.bufferView, size_t(acc.sparse.values.byteOffset),
                                               substitutions * size_t(size) * size_t(components), sparse + " values");
      for (size_t k = 0; k < substitutions; ++k) {
        uint32_t index = read_index(acc.sparse.indices.componentType, indices + k * size_t(index_size));
        if (index >= acc.count)
          fail(sparse + ": substitution " + std::to_string(k) + " names element " + std::to_string(index) + " of " +
               std::to_string(acc.count));
        if (index < count) read_element(values + k * size_t(size) * size_t(components), index);
      }
    }
    return out;
  }

  // Arrays a primitive reads are freed when it is done; they only need to fit beside what the scene holds.
  void charge_transient(uint64_t bytes, const std::string& name) const { budget_.check_fits(bytes, name); }

  // One component at p as a float (see read_floats).
  float component(int type, const unsigned char* p, bool integers, const std::string& name) const {
    auto scaled = [&](double v, double unit) { return float(integers ? v : std::max(v / unit, -1.0)); };
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scaled(*p, 255.0);
      case TINYGLTF_COMPONENT_TYPE_BYTE: return scaled(double(int8_t(*p)), 127.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return scaled(v, 65535.0);
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return scaled(v, 32767.0);
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        if (integers) {
          uint32_t v;
          std::memcpy(&v, p, 4);
          return float(v);
        }
        break;
    }
    fail(name + " has a component type this use cannot read");
  }

  static uint32_t read_index(int type, const unsigned char* p) {
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *p;
    if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t s;
      std::memcpy(&s, p, 2);
      return s;
    }
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }

  // bytes at offset within buffer view `view`, checked to lie inside it and its buffer.
  const unsigned char* view_range(int view, size_t offset, size_t bytes, const std::string& name) const {
    const tinygltf::BufferView& v = buffer_view(view, name);
    if (offset > v.byteLength || bytes > v.byteLength - offset)
      fail(name + ": reads past the end of bufferViews[" + std::to_string(view) + "]");
    return model_.buffers[size_t(v.buffer)].data.data() + v.byteOffset + offset;
  }

  // Buffer view `index`, checked to exist and to lie inside its buffer.
  const tinygltf::BufferView& buffer_view(int index, const std::string& name) const {
    if (index < 0 || size_t(index) >= model_.bufferViews.size()) fail(name + " refers to a missing buffer view");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(index)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(name + " refers to a missing buffer");
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset) {
      fail("bufferViews[" + std::to_string(index) + "] (read by " + name + ") runs past the end of buffers[" +
           std::to_string(view.buffer) + "] (" + std::to_string(buffer.data.size()) + " bytes)");
    }
    return view;
  }

  // A primitive's indices, all of them: their count is what the triangle limit bounds.
  std::vector<uint32_t> read_indices(int accessor_index, const std::string& use) const {
    const tinygltf::Accessor& acc = accessor(accessor_index, use);
    const std::string name = accessor_name(accessor_index, use);
    if (acc.type != TINYGLTF_TYPE_SCALAR) fail(name + " is not SCALAR");
    if (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      fail(name + ": indices must be unsigned byte, short or int");
    if (acc.sparse.isSparse) {  // rare for indices: read as integers (exact below 2^24)
      std::vector<float> values = read_floats(accessor_index, 1, use, true);
      std::vector<uint32_t> out(values.size());
      for (size_t i = 0; i < values.size(); ++i) {
        if (!(values[i] < 16777216.0f)) fail(name + ": a sparse index accessor holds an index beyond 2^24");
        out[i] = uint32_t(values[i]);
      }
      return out;
    }
    const unsigned char* data = nullptr;
    size_t stride = 0;
    element_data(acc, accessor_index, 1, use, &data, &stride);
    charge_transient(uint64_t(acc.count) * sizeof(uint32_t), name);
    std::vector<uint32_t> out(acc.count, 0);
    if (!data) return out;
    for (size_t i = 0; i < acc.count; ++i) out[i] = read_index(acc.componentType, data + i * stride);
    return out;
  }

  const tinygltf::Accessor& accessor(int index, const std::string& use) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
      fail(use + ": accessors[" + std::to_string(index) + "] does not exist");
    return model_.accessors[size_t(index)];
  }

  // Locates an accessor's first element and stride, checking that every element lies inside its buffer; no buffer
  // view: data stays null (zeros).
  void element_data(const tinygltf::Accessor& acc, int index, int components, const std::string& use,
                    const unsigned char** data, size_t* stride) const {
    const std::string name = accessor_name(index, use);
    int component_size = tinygltf::GetComponentSizeInBytes(uint32_t(acc.componentType));
    if (component_size <= 0) fail(name + " has an invalid component type");
    if (acc.bufferView < 0 || zero_accessors_.count(index)) return;
    const tinygltf::BufferView& view = buffer_view(acc.bufferView, name);
    const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    size_t element = size_t(component_size) * size_t(components);
    *stride = view.byteStride ? view.byteStride : element;
    if (*stride < element) fail(name + ": bufferViews[" + std::to_string(acc.bufferView) + "].byteStride is smaller than one element");
    if (acc.count > 0) {
      if (acc.byteOffset > view.byteLength || (acc.count - 1) > (SIZE_MAX - element - acc.byteOffset) / *stride ||
          acc.byteOffset + (acc.count - 1) * *stride + element > view.byteLength) {
        fail(name + ": its " + std::to_string(acc.count) + " elements run past the end of bufferViews[" +
             std::to_string(acc.bufferView) + "] (" + std::to_string(view.byteLength) + " bytes)");
      }
    }
    *data = buffer.data.data() + view.byteOffset + acc.byteOffset;
  }

  // A TRS node's rest translation, rotation and scale (glTF's defaults where one is absent).
  static NodeTrs rest_trs(const tinygltf::Node& node) {
    NodeTrs r;
    if (node.translation.size() == 3) r.translation = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
    if (node.rotation.size() == 4)
      r.rotation = glm::normalize(
          glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
    if (node.scale.size() == 3) r.scale = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
    return r;
  }

  static glm::mat4 local_matrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[size_t(i)]);  // column-major, as glTF
      return m;
    }
    return trs_matrix(rest_trs(node));
  }

  // A node's transform in the pose asked for (ScenePose): the animated TRS where the animation moves it.
  glm::mat4 posed_matrix(int index) const {
    const auto posed = posed_.find(index);
    return posed == posed_.end() ? local_matrix(model_.nodes[size_t(index)]) : posed->second;
  }

  // The pose's node transforms: each channel of the animation sampled at the pose's time over the node's rest TRS.
  void pose_nodes() {
    if (pose_.animation < 0) return;
    if (size_t(pose_.animation) >= model_.animations.size())
      fail("animations[" + std::to_string(pose_.animation) + "]: the file has " +
           std::to_string(model_.animations.size()) + " animation(s)");
    const tinygltf::Animation& anim = model_.animations[size_t(pose_.animation)];
    const std::string name = "animations[" + std::to_string(pose_.animation) + "] '" + printable(anim.name) + "'";
    std::map<int, NodeTrs> trs;
    for (size_t c = 0; c < anim.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = anim.channels[c];
      const int n = channel.target_node;
      if (n < 0 || size_t(n) >= model_.nodes.size()) continue;  // a pointer target (KHR_animation_pointer)
      const std::string where = name + ".channels[" + std::to_string(c) + "]";
      const tinygltf::Node& node = model_.nodes[size_t(n)];
      if (channel.target_path == "weights")
        fail(where + " animates " + node_label(model_, n) + "'s morph weights, which rcsplat does not play (it plays "
             "translation, rotation and scale)");
      AnimatedProperty property;
      if (channel.target_path == "translation") property = AnimatedProperty::translation;
      else if (channel.target_path == "rotation") property = AnimatedProperty::rotation;
      else if (channel.target_path == "scale") property = AnimatedProperty::scale;
      else continue;
      if (node.matrix.size() == 16)
        fail(where + " animates " + node_label(model_, n) + ", which has a matrix (glTF animates nodes given by "
             "translation, rotation and scale only)");
      auto [at, fresh] = trs.try_emplace(n);
      if (fresh) at->second = rest_trs(node);
      apply_track(read_track(pose_.animation, anim.samplers[size_t(channel.sampler)], property,
                             where + " (sampler " + std::to_string(channel.sampler) + ")"),
                  pose_.time, at->second);
    }
    for (const auto& [n, node_trs] : trs) posed_[n] = trs_matrix(node_trs);
    scene_.posed_animation = pose_.animation;
    scene_.posed_time = pose_.time;
  }

  // Adds what node `index` holds under its parent's transform; returns its world transform.
  glm::mat4 visit_node(int index, const glm::mat4& parent) {
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    glm::mat4 world = parent * posed_matrix(index);
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(glm::value_ptr(world)[i])) fail("nodes[" + std::to_string(index) + "] has a non-finite transform");
    NodeContent content{index, world, scene_.triangle_count(), 0, -1};
    if (node.mesh >= 0) add_mesh(index, world);
    content.triangle_count = scene_.triangle_count() - content.first_triangle;
    if (node.camera >= 0) {
      add_camera(node.camera, world);
      camera_nodes_.push_back(index);
    }
    auto ext = node.extensions.find("KHR_lights_punctual");
    const size_t lights_before = scene_.lights.size();
    if (ext != node.extensions.end() && ext->second.Has("light")) add_light(index_value(ext->second.Get("light")), world);
    if (scene_.lights.size() > lights_before) content.light = int(lights_before);
    if (content.triangle_count > 0 || content.light >= 0) content_.push_back(content);
    return world;
  }

  // The triangles a primitive makes (0 for a mode other than triangles), from its accessors' counts alone.
  uint64_t primitive_triangles(const tinygltf::Primitive& prim) const {
    if (prim.mode >= 0 && prim.mode != TINYGLTF_MODE_TRIANGLES) return 0;
    if (prim.indices >= 0) return model_.accessors[size_t(prim.indices)].count / 3;
    auto pos = prim.attributes.find("POSITION");
    return pos == prim.attributes.end() ? 0 : model_.accessors[size_t(pos->second)].count / 3;
  }

  // Refuses, before any triangle is made, a scene that instances more than limits_.max_triangles or more than the
  // host budget holds, naming the mesh that contributes most.
  void check_instanced_triangles(const std::vector<int>& roots) {
    std::vector<uint64_t> mesh_triangles(model_.meshes.size(), 0), mesh_instances(model_.meshes.size(), 0);
    for (size_t m = 0; m < model_.meshes.size(); ++m)
      for (const tinygltf::Primitive& prim : model_.meshes[m].primitives) mesh_triangles[m] += primitive_triangles(prim);
    std::vector<int> stack(roots.begin(), roots.end());
    while (!stack.empty()) {
      const tinygltf::Node& node = model_.nodes[size_t(stack.back())];
      stack.pop_back();
      if (node.mesh >= 0) ++mesh_instances[size_t(node.mesh)];
      stack.insert(stack.end(), node.children.begin(), node.children.end());
    }
    uint64_t total = 0, worst = 0;
    size_t worst_mesh = 0;
    for (size_t m = 0; m < model_.meshes.size(); ++m) {
      const uint64_t t = mesh_triangles[m] * mesh_instances[m];
      total += t;
      if (t > worst) worst = t, worst_mesh = m;
    }
    if (total == 0) return;
    const std::string largest = "meshes[" + std::to_string(worst_mesh) + "] ('" + model_.meshes[worst_mesh].name + "'): " +
                                std::to_string(mesh_triangles[worst_mesh]) + " triangles placed by " +
                                std::to_string(mesh_instances[worst_mesh]) + " node(s)";
    if (total > limits_.max_triangles)
      fail("the scene places " + std::to_string(total) + " triangles, more than the limit of " +
           std::to_string(limits_.max_triangles) + " (--max-triangles); the most from " + largest);
    budget_.charge(total * kHostBytesPerTriangle, std::to_string(total) + " triangles (the most from " + largest + ")");
  }

  // The world transform of every node (parents first), for skins: a joint may sit anywhere in the hierarchy.
  const glm::mat4& node_world(int index) {
    if (node_world_.empty()) {
      node_world_.resize(model_.nodes.size());
      parent_.assign(model_.nodes.size(), -1);
      for (size_t n = 0; n < model_.nodes.size(); ++n)
        for (int c : model_.nodes[n].children)
          if (c >= 0 && size_t(c) < parent_.size()) parent_[size_t(c)] = int(n);
    }
    if (!node_world_[size_t(index)]) {
      std::vector<int> chain{index};  // up to the first ancestor already known, iteratively: a cycle cannot recurse
      for (int up = parent_[size_t(index)]; up >= 0 && !node_world_[size_t(up)]; up = parent_[size_t(up)]) {
        if (chain.size() > model_.nodes.size()) fail("node " + std::to_string(index) + " is its own ancestor (a cycle)");
        chain.push_back(up);
      }
      for (size_t k = chain.size(); k-- > 0;) {
        int n = chain[k], up = parent_[size_t(n)];
        glm::mat4 parent = up >= 0 ? *node_world_[size_t(up)] : glm::mat4(1.0f);
        node_world_[size_t(n)] = parent * posed_matrix(n);
      }
    }
    return *node_world_[size_t(index)];
  }

  // A primitive's vertices and normals after its morph targets at the default weights (node's, else mesh's).
  void apply_morph_targets(const tinygltf::Primitive& prim, const std::vector<double>& weights, const std::string& what,
                           std::vector<float>& pos, std::vector<float>& nrm) const {
    for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
      float w = float(weights[t]);
      if (!std::isfinite(w)) fail(what + ": morph target weight " + std::to_string(t) + " is not finite");
      if (w == 0.0f) continue;
      for (auto [attribute, out] : {std::pair{"POSITION", &pos}, std::pair{"NORMAL", &nrm}}) {
        auto it = prim.targets[t].find(attribute);
        if (it == prim.targets[t].end() || out->empty()) continue;
        const std::string use = what + ".targets[" + std::to_string(t) + "]." + attribute;
        std::vector<float> delta = read_floats(it->second, 3, use, false, out->size() / 3);
        if (delta.size() != out->size()) fail(accessor_name(it->second, use) + " has fewer elements than the primitive's vertices");
        for (size_t i = 0; i < delta.size(); ++i) (*out)[i] += w * delta[i];
      }
    }
  }

  // Skinned vertices in world space, posed by the joints' node transforms (the rest pose a viewer shows without
  // animation): v' = sum_k weight_k * world(joint_k) * inverseBind_k * v. Returns the first vertex's matrix.
  glm::mat4 apply_skin(int skin_index, const tinygltf::Primitive& prim, const std::string& what, std::vector<float>& pos,
                       std::vector<float>& nrm) {
    const tinygltf::Skin& skin = model_.skins[size_t(skin_index)];
    const std::string skin_name = "skins[" + std::to_string(skin_index) + "]";
    auto joints_it = prim.attributes.find("JOINTS_0"), weights_it = prim.attributes.find("WEIGHTS_0");
    if (joints_it == prim.attributes.end() || weights_it == prim.attributes.end())
      fail(what + ": a skinned mesh needs JOINTS_0 and WEIGHTS_0");
    if (prim.attributes.count("JOINTS_1"))
      note_unsupported("more than four joint influences (JOINTS_1)", "only JOINTS_0 and WEIGHTS_0 pose the mesh");
    size_t vertices = pos.size() / 3;
    std::vector<float> joints = read_floats(joints_it->second, 4, what + ".JOINTS_0", true, vertices);
    std::vector<float> weights = read_floats(weights_it->second, 4, what + ".WEIGHTS_0", false, vertices);
    if (joints.size() / 4 != vertices || weights.size() / 4 != vertices)
      fail(what + ": JOINTS_0 and WEIGHTS_0 have fewer elements than POSITION");
    std::vector<glm::mat4> joint_matrix(skin.joints.size(), glm::mat4(1.0f));
    std::vector<float> inverse_bind;
    if (skin.inverseBindMatrices >= 0)  // one matrix a joint is all that is read, whatever the accessor's count
      inverse_bind = read_floats(skin.inverseBindMatrices, 16, skin_name + ".inverseBindMatrices", false, skin.joints.size());
    if (!inverse_bind.empty() && inverse_bind.size() / 16 < skin.joints.size())
      fail(accessor_name(skin.inverseBindMatrices, skin_name + ".inverseBindMatrices") + " holds " +
           std::to_string(inverse_bind.size() / 16) + " matrices for " + std::to_string(skin.joints.size()) + " joints");
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      glm::mat4 bind(1.0f);
      if (!inverse_bind.empty()) std::memcpy(glm::value_ptr(bind), &inverse_bind[16 * j], 16 * sizeof(float));
      joint_matrix[j] = node_world(skin.joints[j]) * bind;
    }
    glm::mat4 first(1.0f);
    for (size_t v = 0; v < vertices; ++v) {
      glm::mat4 m(0.0f);
      for (int k = 0; k < 4; ++k) {
        float w = weights[4 * v + size_t(k)];
        if (w == 0.0f) continue;
        size_t j = size_t(joints[4 * v + size_t(k)]);
        if (j >= joint_matrix.size())
          fail(what + ": vertex " + std::to_string(v) + " names joint " + std::to_string(j) + " of " + skin_name + "'s " +
               std::to_string(joint_matrix.size()));
        m += w * joint_matrix[j];
      }
      if (v == 0) first = m;
      glm::vec3 p = glm::vec3(m * glm::vec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0f));
      for (int c = 0; c < 3; ++c) pos[3 * v + size_t(c)] = p[c];
      if (!nrm.empty()) {
        glm::vec3 n = glm::transpose(glm::inverse(glm::mat3(m))) * glm::vec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
        for (int c = 0; c < 3; ++c) nrm[3 * v + size_t(c)] = n[c];
      }
    }
    return first;
  }

  void add_mesh(int node_index, const glm::mat4& node_matrix) {
    const tinygltf::Node& node = model_.nodes[size_t(node_index)];
    int mesh_index = node.mesh;
    const tinygltf::Mesh& mesh = model_.meshes[size_t(mesh_index)];
    const std::vector<double>& morph_weights = node.weights.empty() ? mesh.weights : node.weights;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      // A skinned mesh is placed by its joints alone (the specification ignores the mesh node's own transform).
      glm::mat4 world = node.skin >= 0 ? glm::mat4(1.0f) : node_matrix;
      const tinygltf::Primitive& prim = mesh.primitives[p];
      const std::string what = "meshes[" + std::to_string(mesh_index) + "].primitives[" + std::to_string(p) + "]";
      int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES) {
        warn(what + " ('" + mesh.name + "'): primitive mode " + std::to_string(mode) +
             " is not triangles; rcsplat renders only triangle lists, so this primitive is skipped");
        continue;
      }
      auto pos_it = prim.attributes.find("POSITION");
      if (pos_it == prim.attributes.end()) fail(what + ": no POSITION attribute");
      const size_t position_count = accessor(pos_it->second, what + ".POSITION").count;
      // Indices first: the vertices they reach are all that is read of every attribute.
      std::vector<uint32_t> idx;
      if (prim.indices >= 0) {
        idx = read_indices(prim.indices, what + ".indices");
      } else {
        charge_transient(uint64_t(position_count) * sizeof(uint32_t), what + " (its vertex order)");
        idx.resize(position_count);
        for (size_t i = 0; i < position_count; ++i) idx[i] = uint32_t(i);
      }
      if (idx.size() % 3 != 0) fail(what + ": index count " + std::to_string(idx.size()) + " is not a multiple of 3");
      size_t vertex_count = 0;
      for (size_t i = 0; i < idx.size(); ++i) {
        if (idx[i] >= position_count) {
          fail(accessor_name(prim.indices, what + ".indices") + ": index " + std::to_string(idx[i]) + " at position " +
               std::to_string(i) + " is out of range (POSITION has " + std::to_string(position_count) + " vertices)");
        }
        vertex_count = std::max(vertex_count, size_t(idx[i]) + 1);
      }
      std::vector<float> pos = read_floats(pos_it->second, 3, what + ".POSITION", false, vertex_count);
      std::vector<float> nrm, uv, color;
      auto n_it = prim.attributes.find("NORMAL");
      if (n_it != prim.attributes.end()) nrm = read_floats(n_it->second, 3, what + ".NORMAL", false, vertex_count);
      if (nrm.empty() || nrm.size() == pos.size()) apply_morph_targets(prim, morph_weights, what, pos, nrm);
      glm::mat4 skin_matrix(1.0f);
      if (node.skin >= 0) skin_matrix = apply_skin(node.skin, prim, what, pos, nrm);
      for (size_t i = 0; i < pos.size(); ++i)
        if (!std::isfinite(pos[i])) fail(what + ": vertex " + std::to_string(i / 3) + " has a non-finite position");
      for (size_t i = 0; i < nrm.size(); ++i)
        if (!std::isfinite(nrm[i])) fail(what + ": vertex " + std::to_string(i / 3) + " has a non-finite normal");
      glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(world)));
      // A mirroring transform flips the winding (for a skin, judged by its first vertex's matrix).
      bool mirrored = glm::determinant(glm::mat3(node.skin >= 0 ? skin_matrix : world)) < 0.0f;
      auto c_it = prim.attributes.find("COLOR_0");
      if (c_it != prim.attributes.end()) {
        int components = accessor(c_it->second, what + ".COLOR_0").type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
        std::vector<float> rgba = read_floats(c_it->second, components, what + ".COLOR_0", false, vertex_count);
        color.resize(rgba.size() / size_t(components) * 3);
        for (size_t v = 0; v < color.size() / 3; ++v)
          for (int c = 0; c < 3; ++c) color[3 * v + size_t(c)] = std::clamp(rgba[v * size_t(components) + size_t(c)], 0.0f, 1.0f);
      }
      uint32_t material = material_slot(prim.material, what);
      UvMapping mapping = base_color_uv_mapping(prim.material);
      auto uv_it = prim.attributes.find("TEXCOORD_" + std::to_string(mapping.tex_coord));
      if (uv_it != prim.attributes.end())
        uv = read_floats(uv_it->second, 2, what + ".TEXCOORD_" + std::to_string(mapping.tex_coord), false, vertex_count);
      for (size_t v = 0; v < uv.size() / 2; ++v) {  // KHR_texture_transform, applied once here
        glm::vec3 t = mapping.transform * glm::vec3(uv[2 * v], uv[2 * v + 1], 1.0f);
        uv[2 * v] = t.x;
        uv[2 * v + 1] = t.y;
      }
      if ((!nrm.empty() && nrm.size() != pos.size()) || (!uv.empty() && uv.size() / 2 != vertex_count) ||
          (!color.empty() && color.size() != pos.size()))
        fail(what + ": attributes have different vertex counts");
      std::vector<glm::vec4> tangents;
      if (normal_mapped(int(material))) {
        if (uv.empty())
          note_unsupported("normalTexture on a primitive without texture coordinates", "its interpolated normals shade it");
        else
          tangents = primitive_tangents(prim, node, morph_weights, what, idx, pos, nrm, uv, world, normal_matrix, mirrored);
      }
      size_t first = scene_.positions.size();
      for (size_t t = 0; t < idx.size(); t += 3)
        add_triangle(t, idx, {pos, nrm, uv, color, tangents}, world, normal_matrix, mirrored, material);
      for (size_t i = first; i < scene_.positions.size(); ++i)
        if (!std::isfinite(scene_.positions[i].x + scene_.positions[i].y + scene_.positions[i].z))
          fail(what + ": the node's transform takes a vertex beyond the range of single precision");
    }
  }

  // The tangents of a normal-mapped primitive's triangle corners (in `idx`'s order) in world space (Scene::tangents),
  // w = +-1: the file's TANGENT where it has one and nothing deforms the mesh; otherwise made from the posed positions
  // and texture coordinates (generate_tangents).
  std::vector<glm::vec4> primitive_tangents(const tinygltf::Primitive& prim, const tinygltf::Node& node,
                                            const std::vector<double>& morph_weights, const std::string& what,
                                            const std::vector<uint32_t>& idx, const std::vector<float>& pos,
                                            const std::vector<float>& nrm, const std::vector<float>& uv,
                                            const glm::mat4& world, const glm::mat3& normal_matrix, bool mirrored) {
    const size_t vertices = pos.size() / 3;
    bool morphed = false;
    for (size_t t = 0; t < prim.targets.size() && t < morph_weights.size(); ++t) morphed |= morph_weights[t] != 0.0;
    auto it = prim.attributes.find("TANGENT");
    if (it != prim.attributes.end() && node.skin < 0 && !morphed) {
      std::vector<float> file = read_floats(it->second, 4, what + ".TANGENT", false, vertices);
      if (file.size() / 4 != vertices) fail(what + ": TANGENT has fewer elements than POSITION");
      std::vector<glm::vec4> per_vertex(vertices);
      // A mirroring transform turns the bitangent the other way relative to cross(normal, tangent).
      const float handedness = mirrored ? -1.0f : 1.0f;
      for (size_t v = 0; v < vertices; ++v) {
        glm::vec3 t = glm::mat3(world) * glm::vec3(file[4 * v], file[4 * v + 1], file[4 * v + 2]);
        float len = glm::length(t), w = file[4 * v + 3];
        if (!std::isfinite(len) || !std::isfinite(w)) fail(what + ": vertex " + std::to_string(v) + " has a non-finite TANGENT");
        per_vertex[v] = glm::vec4(len > 0.0f ? t / len : glm::vec3(0.0f), (w < 0.0f ? -1.0f : 1.0f) * handedness);
      }
      std::vector<glm::vec4> out(idx.size());
      for (size_t c = 0; c < idx.size(); ++c) out[c] = per_vertex[idx[c]];
      return out;
    }
    std::vector<glm::vec3> world_pos(vertices), world_nrm;
    for (size_t v = 0; v < vertices; ++v) world_pos[v] = glm::vec3(world * glm::vec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0f));
    if (!nrm.empty()) {
      world_nrm.resize(vertices);
      for (size_t v = 0; v < vertices; ++v) world_nrm[v] = normal_matrix * glm::vec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2]);
    }
    return generate_tangents(idx, world_pos, world_nrm, uv);
  }

  struct VertexArrays {
    const std::vector<float>&pos, &nrm, &uv, &color;  // color: linear RGB, empty when the primitive has none
    const std::vector<glm::vec4>& tangents;          // world space, per corner (idx's order); empty without a map
  };

  void add_triangle(size_t t, const std::vector<uint32_t>& idx, const VertexArrays& v, const glm::mat4& world,
                    const glm::mat3& normal_matrix, bool mirrored, uint32_t material) {
    const std::vector<float>&pos = v.pos, &nrm = v.nrm, &uv = v.uv;
    uint32_t order[3] = {idx[t], idx[t + 1], idx[t + 2]};
    size_t corner[3] = {t, t + 1, t + 2};
    if (mirrored) {
      std::swap(order[1], order[2]);
      std::swap(corner[1], corner[2]);
    }
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = glm::vec3(world * glm::vec4(pos[3 * order[k]], pos[3 * order[k] + 1], pos[3 * order[k] + 2], 1.0f));
    scene_.add_triangle(p[0], p[1], p[2], material);
    size_t base = scene_.normals.size() - 3;
    glm::vec3 geometric = scene_.normals[base];
    for (int k = 0; k < 3; ++k) {
      if (!nrm.empty()) {
        glm::vec3 n = normal_matrix * glm::vec3(nrm[3 * order[k]], nrm[3 * order[k] + 1], nrm[3 * order[k] + 2]);
        float len = glm::length(n);
        // A zero normal (common in exported meshes) falls back to the geometric one; non-finite ones are refused on
        // reading.
        scene_.normals[base + size_t(k)] = len > 0.0f && std::isfinite(len) ? n / len : geometric;
      }
      if (!uv.empty()) {
        glm::vec2 u(uv[2 * order[k]], uv[2 * order[k] + 1]);
        scene_.uvs[base + size_t(k)] = (std::isfinite(u.x) && std::isfinite(u.y)) ? u : glm::vec2(0.0f);
      }
      if (!v.tangents.empty()) {
        // Triangles added before the first normal map get zero tangents: w = 0 says "no map here" to the kernels.
        if (scene_.tangents.size() < scene_.positions.size()) scene_.tangents.resize(scene_.positions.size(), glm::vec4(0.0f));
        scene_.tangents[base + size_t(k)] = v.tangents[corner[k]];
      }
      if (!v.color.empty()) {
        glm::vec3 c(v.color[3 * order[k]], v.color[3 * order[k] + 1], v.color[3 * order[k] + 2]);
        scene_.colors[base + size_t(k)] = (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) ? c : glm::vec3(1.0f);
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
      m.metallic = m.roughness = m.specular = 1.0f;  // the specification's default material
      default_material_ = int(scene_.materials.size());
      scene_.materials.push_back(m);
    }
    return uint32_t(default_material_);
  }

  // Which TEXCOORD set the base colour texture reads, and KHR_texture_transform's matrix for it:
  // translation * rotation * scale, applied to (u, v, 1).
  struct UvMapping {
    int tex_coord = 0;
    glm::mat3 transform{1.0f};
  };
  // The mapping a texture reference asks for: its TEXCOORD set and KHR_texture_transform.
  template <typename Info>  // tinygltf's TextureInfo, NormalTextureInfo or OcclusionTextureInfo
  static UvMapping uv_mapping_of(const Info& info) {
    UvMapping m;
    m.tex_coord = info.texCoord;
    auto ext = info.extensions.find("KHR_texture_transform");
    if (ext == info.extensions.end()) return m;
    const tinygltf::Value& t = ext->second;
    auto pair = [&](const char* key, glm::vec2 fallback) {
      if (!t.Has(key) || !t.Get(key).IsArray() || t.Get(key).ArrayLen() != 2) return fallback;
      return glm::vec2(float(t.Get(key).Get(0).GetNumberAsDouble()), float(t.Get(key).Get(1).GetNumberAsDouble()));
    };
    glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
    float rotation = t.Has("rotation") ? float(t.Get("rotation").GetNumberAsDouble()) : 0.0f;
    if (t.Has("texCoord")) m.tex_coord = index_value(t.Get("texCoord"));
    float c = std::cos(rotation), s = std::sin(rotation);
    // The extension's GLSL, column by column: rotation = mat3(c, s, 0, -s, c, 0, 0, 0, 1).
    glm::mat3 translate(1.0f), rotate(1.0f), scaling(1.0f);
    translate[2] = glm::vec3(offset, 1.0f);
    rotate[0] = glm::vec3(c, s, 0.0f);
    rotate[1] = glm::vec3(-s, c, 0.0f);
    scaling[0][0] = scale.x;
    scaling[1][1] = scale.y;
    m.transform = translate * rotate * scaling;
    return m;
  }

  // The one texture-coordinate mapping a material's triangles carry: the base colour texture's, else the
  // metallic-roughness texture's (a metallic-roughness texture mapped differently is dropped in read_materials).
  UvMapping base_color_uv_mapping(int index) const {
    if (index < 0 || size_t(index) >= model_.materials.size()) return UvMapping{};
    const tinygltf::Material& m = model_.materials[size_t(index)];
    const auto& pbr = m.pbrMetallicRoughness;
    // The first texture the material has, in this order, sets the mapping; textures mapped otherwise are named and
    // dropped in read_materials.
    if (pbr.baseColorTexture.index >= 0) return uv_mapping_of(pbr.baseColorTexture);
    if (pbr.metallicRoughnessTexture.index >= 0) return uv_mapping_of(pbr.metallicRoughnessTexture);
    if (m.normalTexture.index >= 0) return uv_mapping_of(m.normalTexture);
    return uv_mapping_of(m.emissiveTexture);
  }

  // Whether material `index` keeps a normal map (read_materials decided): its primitives then carry tangents.
  bool normal_mapped(int index) const {
    if (index < 0 || size_t(index) >= scene_.materials.size()) return false;
    const SceneMaterial& m = scene_.materials[size_t(index)];
    return m.normal_texture >= 0 || (m.clearcoat > 0.0f && m.clearcoat_normal_texture >= 0);
  }

  static bool same_mapping(const UvMapping& a, const UvMapping& b) {
    return a.tex_coord == b.tex_coord && a.transform == b.transform;
  }

  int texture_slot(int tex, const std::string& material) const {
    if (tex < 0) return -1;
    if (size_t(tex) >= texture_slots_.size()) fail("material '" + material + "': textures[" + std::to_string(tex) + "] does not exist");
    return texture_slots_[size_t(tex)];
  }

  // "materials[3] 'marble'" for messages.
  std::string material_label(const tinygltf::Material& src) const {
    return "materials[" + std::to_string(&src - model_.materials.data()) + "] '" + src.name + "'";
  }

  // A texture an extension names (`key` in `extension`, e.g. KHR_materials_specular's specularTexture), where it is
  // mapped as the material's other textures; -1 where it has none, or is mapped otherwise (named: `instead` is used).
  int extension_texture_slot(const tinygltf::Material& src, const tinygltf::Value& extension, const std::string& name,
                             const char* key, const char* instead) {
    if (!extension.Has(key)) return -1;
    const tinygltf::Value& info = extension.Get(key);
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsNumber())
      fail(material_label(src) + ": " + name + "'s " + key + " has no texture index");
    const double index = info.Get("index").GetNumberAsDouble();
    if (!(index >= 0.0) || index != std::floor(index) || index >= double(model_.textures.size()))
      fail(material_label(src) + ": " + name + "'s " + key + " names no texture of the file");
    UvMapping mapping;
    if (info.Has("texCoord") && info.Get("texCoord").IsNumber()) mapping.tex_coord = int(info.Get("texCoord").GetNumberAsDouble());
    if (info.Has("extensions") || !same_mapping(mapping, base_color_uv_mapping(int(&src - model_.materials.data())))) {
      note_unsupported(std::string(key) + " mapped unlike the material's other textures", instead);
      return -1;
    }
    return texture_slot(int(index), src.name);
  }

  // A number an extension gives, or `fallback` where it gives none; a value that is not a number is refused.
  double extension_number(const tinygltf::Material& src, const tinygltf::Value& extension, const std::string& name,
                          const char* key, double fallback) const {
    if (!extension.Has(key)) return fallback;
    const tinygltf::Value& v = extension.Get(key);
    if (!v.IsNumber()) fail(material_label(src) + ": " + name + "'s " + key + " is not a number");
    return v.GetNumberAsDouble();
  }

  // Three numbers an extension gives (a colour), each finite and in [0, most]; `fallback` where it gives none.
  glm::vec3 extension_colour(const tinygltf::Material& src, const tinygltf::Value& extension, const std::string& name,
                             const char* key, glm::vec3 fallback, double most) const {
    if (!extension.Has(key)) return fallback;
    const tinygltf::Value& c = extension.Get(key);
    if (!c.IsArray() || c.ArrayLen() != 3) fail(material_label(src) + ": " + name + "'s " + key + " is not three numbers");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      const double x = c.Get(i).IsNumber() ? c.Get(i).GetNumberAsDouble() : NAN;
      if (!std::isfinite(x) || x < 0.0 || x > most)
        fail(material_label(src) + ": " + name + "'s " + key + " must be three finite numbers in [0, " +
             (std::isfinite(most) ? std::to_string(int(most)) : std::string("infinity")) + ")");
      out[i] = float(x);
    }
    return out;
  }

  // A factor an extension gives in [0, 1], or `fallback`.
  float extension_unit(const tinygltf::Material& src, const tinygltf::Value& extension, const std::string& name,
                       const char* key, double fallback) const {
    const double x = extension_number(src, extension, name, key, fallback);
    if (!std::isfinite(x) || x < 0.0 || x > 1.0) fail(material_label(src) + ": " + name + "'s " + key + " must lie in [0, 1]");
    return float(x);
  }

  // Layers: KHR_materials_clearcoat and KHR_materials_sheen (kernels/brdf_layers.h simulates them).
  void read_layers(const tinygltf::Material& src, SceneMaterial& m) {
    auto coat = src.extensions.find("KHR_materials_clearcoat");
    if (coat != src.extensions.end()) {
      const std::string name = "KHR_materials_clearcoat";
      const tinygltf::Value& v = coat->second;
      m.clearcoat = extension_unit(src, v, name, "clearcoatFactor", 0.0);
      m.clearcoat_roughness = extension_unit(src, v, name, "clearcoatRoughnessFactor", 0.0);
      m.clearcoat_texture = extension_texture_slot(src, v, name, "clearcoatTexture", "clearcoatFactor alone is used");
      m.clearcoat_roughness_texture = extension_texture_slot(src, v, name, "clearcoatRoughnessTexture",
                                                             "clearcoatRoughnessFactor alone is used");
      m.clearcoat_normal_texture = extension_texture_slot(src, v, name, "clearcoatNormalTexture",
                                                          "the coat follows the interpolated normal");
      if (m.clearcoat_normal_texture >= 0) {
        const tinygltf::Value& info = v.Get("clearcoatNormalTexture");
        m.clearcoat_normal_scale = 1.0f;
        if (info.Has("scale")) {
          const tinygltf::Value& scale = info.Get("scale");
          const double x = scale.IsNumber() ? scale.GetNumberAsDouble() : NAN;
          if (!std::isfinite(x)) fail(material_label(src) + ": " + name + "'s clearcoatNormalTexture.scale is not finite");
          m.clearcoat_normal_scale = float(x);
        }
      }
    }
    auto sheen = src.extensions.find("KHR_materials_sheen");
    if (sheen != src.extensions.end()) {
      const std::string name = "KHR_materials_sheen";
      const tinygltf::Value& v = sheen->second;
      m.sheen_color = extension_colour(src, v, name, "sheenColorFactor", glm::vec3(0.0f), 1.0);
      m.sheen_roughness = extension_unit(src, v, name, "sheenRoughnessFactor", 0.0);
      m.sheen_color_texture = extension_texture_slot(src, v, name, "sheenColorTexture", "sheenColorFactor alone is used");
      m.sheen_roughness_texture = extension_texture_slot(src, v, name, "sheenRoughnessTexture",
                                                         "sheenRoughnessFactor alone is used");
    }
    if (m.layered() && m.transmission > 0.0f)
      note_unsupported("clearcoat, sheen or specular colour on glass", "the glass's surface reflects as uncoated glass");
  }

  // Glass: KHR_materials_transmission, KHR_materials_ior and KHR_materials_volume (kernels/glass.h simulates them).
  void read_glass(const tinygltf::Material& src, SceneMaterial& m) {
    auto transmission = src.extensions.find("KHR_materials_transmission");
    if (transmission != src.extensions.end()) {
      const std::string name = "KHR_materials_transmission";
      const double factor = extension_number(src, transmission->second, name, "transmissionFactor", 0.0);
      if (!std::isfinite(factor) || factor < 0.0 || factor > 1.0)
        fail(material_label(src) + ": " + name + "'s transmissionFactor must lie in [0, 1]");
      m.transmission = float(factor);
      m.transmission_texture = extension_texture_slot(src, transmission->second, name, "transmissionTexture",
                                                      "transmissionFactor alone is used");
    }
    auto ior = src.extensions.find("KHR_materials_ior");
    if (ior != src.extensions.end()) {
      const double value = extension_number(src, ior->second, "KHR_materials_ior", "ior", 1.5);
      if (!std::isfinite(value) || value < 1.0)
        fail(material_label(src) + ": KHR_materials_ior's ior is " + std::to_string(value) +
             "; an index of refraction must be a finite number of at least 1");
      m.ior = float(value);
    }
    auto volume = src.extensions.find("KHR_materials_volume");
    if (volume != src.extensions.end()) {
      const std::string name = "KHR_materials_volume";
      const tinygltf::Value& v = volume->second;
      const double thickness = extension_number(src, v, name, "thicknessFactor", 0.0);
      const double distance = extension_number(src, v, name, "attenuationDistance", INFINITY);
      if (!std::isfinite(thickness) || thickness < 0.0)
        fail(material_label(src) + ": " + name + "'s thicknessFactor must be a finite number of at least 0");
      if (std::isnan(distance) || distance <= 0.0)
        fail(material_label(src) + ": " + name + "'s attenuationDistance must be above 0");
      m.thickness = float(thickness);
      m.attenuation_distance = float(distance);
      if (v.Has("attenuationColor")) {
        const tinygltf::Value& c = v.Get("attenuationColor");
        if (!c.IsArray() || c.ArrayLen() != 3) fail(material_label(src) + ": " + name + "'s attenuationColor is not three numbers");
        for (int i = 0; i < 3; ++i) {
          const double x = c.Get(i).IsNumber() ? c.Get(i).GetNumberAsDouble() : NAN;
          if (!std::isfinite(x) || x < 0.0 || x > 1.0)
            fail(material_label(src) + ": " + name + "'s attenuationColor must be three numbers in [0, 1]");
          m.attenuation_color[i] = float(x);
        }
      }
      // A rasterizer's stand-in for the volume it cannot trace; rcsplat traces the mesh's own.
      if (v.Has("thicknessTexture"))
        note_unsupported("KHR_materials_volume thicknessTexture", "not read: rays cross the mesh's own volume");
    }
    if (m.transmission == 0.0f && m.ior != 1.5f)
      note_unsupported("KHR_materials_ior on opaque materials", "their specular layer keeps ior 1.5's reflectance (0.04)");
    if (m.transmission > 0.0f && m.roughness > 0.0f)
      note_unsupported("rough transmission (frosted glass)", "light passes glass as through a smooth surface");
  }

  // metallicFactor, roughnessFactor (glTF defaults 1 and 1), their texture, and KHR_materials_specular's factor.
  void read_brdf(const tinygltf::Material& src, SceneMaterial& m) {
    const auto& pbr = src.pbrMetallicRoughness;
    m.metallic = float(pbr.metallicFactor);
    m.roughness = float(pbr.roughnessFactor);
    m.specular = 1.0f;
    auto ext = src.extensions.find("KHR_materials_specular");
    if (ext != src.extensions.end()) {
      const tinygltf::Value& v = ext->second;
      if (v.Has("specularFactor")) m.specular = float(v.Get("specularFactor").GetNumberAsDouble());
      // The extension allows colours above 1 (F0 = 0.04 x colour is clamped at 1 later): finite and at least 0.
      m.specular_color = extension_colour(src, v, "KHR_materials_specular", "specularColorFactor", glm::vec3(1.0f),
                                          std::numeric_limits<double>::infinity());
      m.specular_texture = extension_texture_slot(src, v, "KHR_materials_specular", "specularTexture",
                                                  "specularFactor alone is used");
      m.specular_color_texture = extension_texture_slot(src, v, "KHR_materials_specular", "specularColorTexture",
                                                        "specularColorFactor alone is used");
    }
    for (float f : {m.metallic, m.roughness, m.specular})
      if (!std::isfinite(f) || f < 0.0f || f > 1.0f)
        fail(material_label(src) + ": metallicFactor, roughnessFactor and specularFactor must lie in [0, 1]");
    m.metallic_roughness_texture = texture_slot(pbr.metallicRoughnessTexture.index, src.name);
    if (m.metallic_roughness_texture >= 0 && pbr.baseColorTexture.index >= 0 &&
        !same_mapping(uv_mapping_of(pbr.baseColorTexture), uv_mapping_of(pbr.metallicRoughnessTexture))) {
      note_unsupported("metallicRoughnessTexture mapped unlike the base colour texture", "the factors alone are used");
      m.metallic_roughness_texture = -1;
    }
  }

  void read_materials() {
    for (const tinygltf::Material& src : model_.materials) {
      SceneMaterial m;
      m.name = printable(src.name);  // a stranger's text, shown in summaries and JSON
      const auto& pbr = src.pbrMetallicRoughness;
      for (int i = 0; i < 4 && size_t(i) < pbr.baseColorFactor.size(); ++i) m.base_color[i] = float(pbr.baseColorFactor[size_t(i)]);
      m.base_color_texture = texture_slot(pbr.baseColorTexture.index, src.name);
      read_brdf(src, m);
      read_glass(src, m);
      read_layers(src, m);
      float strength = 1.0f;
      auto ext = src.extensions.find("KHR_materials_emissive_strength");
      if (ext != src.extensions.end() && ext->second.Has("emissiveStrength"))
        strength = float(ext->second.Get("emissiveStrength").GetNumberAsDouble());
      for (int i = 0; i < 3 && size_t(i) < src.emissiveFactor.size(); ++i) m.emission[i] = float(src.emissiveFactor[size_t(i)]) * strength;
      m.double_sided = src.doubleSided;
      for (int i = 0; i < 4; ++i)
        if (!std::isfinite(m.base_color[i]) || m.base_color[i] < 0.0f) fail(material_label(src) + ": invalid baseColorFactor");
      for (int i = 0; i < 3; ++i)
        if (!std::isfinite(m.emission[i]) || m.emission[i] < 0.0f) fail(material_label(src) + ": invalid emission");
      if (m.clearcoat > 0.0f && m.transmission == 0.0f && (m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f))
        note_unsupported("clearcoat over emission", "the emission is not dimmed by the coat's Fresnel");
      // Triangles carry one texture-coordinate mapping (base_color_uv_mapping): a texture mapped otherwise is named
      // and left out.
      const UvMapping mapping = base_color_uv_mapping(int(&src - model_.materials.data()));
      auto same_mapped = [&](const auto& info, const std::string& what, const char* instead) {
        if (info.index < 0) return -1;
        if (!same_mapping(uv_mapping_of(info), mapping)) {
          note_unsupported(what + " mapped unlike the material's other textures", instead);
          return -1;
        }
        return texture_slot(info.index, src.name);
      };
      m.emissive_texture = same_mapped(src.emissiveTexture, "emissiveTexture", "emissiveFactor alone is used");
      m.normal_texture = same_mapped(src.normalTexture, "normalTexture", "the interpolated vertex normals shade");
      m.normal_scale = float(src.normalTexture.scale);
      if (m.normal_texture >= 0 && !std::isfinite(m.normal_scale))
        fail(material_label(src) + ": normalTexture.scale is not finite");
      // Named, never dropped silently: a baked occlusion that light transport computes.
      if (src.occlusionTexture.index >= 0)
        note_unsupported("occlusionTexture", "not applied: the indirect light's occlusion is traced, not baked");
      if (src.alphaMode == "MASK") {
        // A cutoff of 0 would make every hit solid: keep the smallest positive one instead.
        m.alpha_cutoff = std::max(float(src.alphaCutoff), 1e-6f);
        if (!std::isfinite(m.alpha_cutoff)) fail(material_label(src) + ": invalid alphaCutoff");
      } else if (src.alphaMode == "BLEND") {
        m.alpha_blend = true;
      }
      scene_.materials.push_back(m);
    }
  }

  static int wrap_mode(int gl) {
    if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WRAP_CLAMP;
    if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WRAP_MIRROR;
    return WRAP_REPEAT;
  }

  // The image a texture reads: EXT_texture_webp's source where it names one (rcsplat decodes WebP), else "source"
  // (the fallback the extension lets a file give for readers without WebP).
  int texture_source(const tinygltf::Texture& tex, size_t index) const {
    auto ext = tex.extensions.find("EXT_texture_webp");
    if (ext == tex.extensions.end() || !ext->second.Has("source")) return tex.source;
    const tinygltf::Value& v = ext->second.Get("source");
    const double source = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(source >= 0.0) || source >= double(model_.images.size()) || source != std::floor(source))
      fail("textures[" + std::to_string(index) + "]: EXT_texture_webp's source is not an image of the file");
    return int(source);
  }

  // glTF textures become scene textures (RGBA8). A texture without an image (valid glTF: an extension may supply
  // one) leaves its materials untextured, with a warning; an image that did not decode was refused by the loader.
  void read_textures() {
    for (size_t t = 0; t < model_.textures.size(); ++t) {
      const tinygltf::Texture& tex = model_.textures[t];
      int slot = -1;
      const int source = texture_source(tex, t);
      if (source >= 0 && size_t(source) < model_.images.size()) {
        const tinygltf::Image& img = model_.images[size_t(source)];
        if (img.width > 0 && img.height > 0 && (img.bits == 8 || img.bits == 16) && img.component >= 1 &&
            img.component <= 4 && img.image.size() >= size_t(img.width) * size_t(img.height) * size_t(img.component) * size_t(img.bits / 8)) {
          SceneTexture out;
          out.name = printable(img.uri.empty() ? img.name : img.uri);
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
            const tinygltf::Sampler& sampler = model_.samplers[size_t(tex.sampler)];
            out.wrap_s = wrap_mode(sampler.wrapS);
            out.wrap_t = wrap_mode(sampler.wrapT);
            out.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            // Minified through the mip chain by each ray's footprint, unless the sampler asks for no mipmaps.
            const int min = sampler.minFilter;
            out.mipmaps = min != TINYGLTF_TEXTURE_FILTER_NEAREST && min != TINYGLTF_TEXTURE_FILTER_LINEAR;
          }
          slot = int(scene_.textures.size());
          scene_.textures.push_back(std::move(out));
        }
      }
      if (slot < 0) {
        if (source >= 0) {
          const tinygltf::Image& img = model_.images[size_t(source)];
          fail("textures[" + std::to_string(t) + "]: images[" + std::to_string(source) + "] '" +
               (img.uri.empty() ? img.name : img.uri.substr(0, 80)) + "' holds no pixels rcsplat can use");
        }
        warn("textures[" + std::to_string(t) + "] has no image (\"source\"); materials that use it are untextured");
      }
      texture_slots_.push_back(slot);
    }
  }

  void add_camera(int index, const glm::mat4& world) {
    if (size_t(index) >= model_.cameras.size()) fail("camera " + std::to_string(index) + " does not exist");
    const tinygltf::Camera& cam = model_.cameras[size_t(index)];
    SceneCamera c;
    c.name = cam.name.empty() ? "camera " + std::to_string(index) : printable(cam.name);
    if (cam.type == "orthographic") {
      c.orthographic = true;
      c.xmag = float(std::abs(cam.orthographic.xmag));
      c.ymag = float(std::abs(cam.orthographic.ymag));
      if (!(c.xmag > 0.0f && c.ymag > 0.0f && std::isfinite(c.xmag) && std::isfinite(c.ymag)))
        fail("cameras[" + std::to_string(index) + "] ('" + c.name + "') has an invalid xmag or ymag");
      c.aspect = c.xmag / c.ymag;
    } else if (cam.type != "perspective") {
      fail("cameras[" + std::to_string(index) + "] ('" + c.name + "') has unknown type '" + cam.type + "'");
    }
    c.eye = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    glm::vec3 forward = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    c.target = c.eye + forward;
    c.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
    if (!c.orthographic) {
      c.yfov = float(cam.perspective.yfov);
      if (!(c.yfov > 0.0f && c.yfov < 3.1f)) fail("cameras[" + std::to_string(index) + "] ('" + c.name + "') has an invalid yfov");
      if (cam.perspective.aspectRatio > 0.0) c.aspect = float(cam.perspective.aspectRatio);
    }
    scene_.cameras.push_back(c);
  }

  void add_light(int index, const glm::mat4& world) {
    if (index < 0 || size_t(index) >= model_.lights.size()) fail("light " + std::to_string(index) + " does not exist");
    const tinygltf::Light& src = model_.lights[size_t(index)];
    const std::string light_label = "extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "] '" + src.name + "'";
    SceneLight l;
    l.name = printable(src.name);
    if (src.type == "point") l.type = LightType::point;
    else if (src.type == "spot") l.type = LightType::spot;
    else if (src.type == "directional") l.type = LightType::directional;
    else fail(light_label + " has unknown type '" + src.type + "'");
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
      fail(light_label + " has an invalid colour, intensity or orientation");
    scene_.lights.push_back(l);
  }

  static std::string node_label(const tinygltf::Model& model, int index) {
    return "nodes[" + std::to_string(index) + "] '" + printable(model.nodes[size_t(index)].name) + "'";
  }

  // One channel's keys, checked as glTF requires: times finite and strictly increasing, one value per time (three
  // for a cubic spline), every value finite.
  AnimationTrack read_track(int animation, const tinygltf::AnimationSampler& sampler, AnimatedProperty property,
                            const std::string& where) {
    AnimationTrack track;
    track.animation = animation;
    track.property = property;
    if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") track.interpolation = AnimationInterpolation::linear;
    else if (sampler.interpolation == "STEP") track.interpolation = AnimationInterpolation::step;
    else if (sampler.interpolation == "CUBICSPLINE") track.interpolation = AnimationInterpolation::cubic_spline;
    else fail(where + " has unknown interpolation '" + printable(sampler.interpolation) + "'");
    track.times = read_floats(sampler.input, 1, where + ".input");
    if (track.times.empty()) fail(where + ".input has no keys");
    for (size_t k = 0; k < track.times.size(); ++k)
      if (!std::isfinite(track.times[k]) || track.times[k] < 0.0f || (k && !(track.times[k] > track.times[k - 1])))
        fail(where + ".input: key " + std::to_string(k) + "'s time is not finite, not positive or not after the one "
             "before it");
    const int components = property == AnimatedProperty::rotation ? 4 : 3;
    const size_t per_key = track.interpolation == AnimationInterpolation::cubic_spline ? 3 : 1;
    track.values = read_floats(sampler.output, components, where + ".output");
    if (track.values.size() != track.times.size() * per_key * size_t(components))
      fail(where + ".output holds " + std::to_string(track.values.size() / size_t(components)) + " elements for " +
           std::to_string(track.times.size()) + " keys (" + std::to_string(per_key) + " a key expected)");
    for (float v : track.values)
      if (!std::isfinite(v)) fail(where + ".output holds a value that is not finite");
    return track;
  }

  // A link of a camera's or a mover's chain: node n at rest (read_animations gives it its channels).
  RigNode rig_node(int n) const {
    const tinygltf::Node& node = model_.nodes[size_t(n)];
    RigNode r;
    r.label = node_label(model_, n);
    r.has_matrix = node.matrix.size() == 16;
    r.matrix = local_matrix(node);
    r.rest = rest_trs(node);
    return r;
  }

  // In read_animations' map of where each node sits in a rig, a mover's rig is numbered from here on.
  static constexpr size_t kMoverRig = size_t(1) << 40;

  // Scene::movers: every node that placed a mesh or a light and that a channel moves (on the node, above it, or on a
  // joint of its skin), with its chain of nodes; read_animations gives the chains' nodes their channels.
  void read_movers(const std::vector<int>& parent, std::vector<std::vector<std::pair<size_t, size_t>>>& in_rigs,
                   size_t& rig_nodes, size_t max_rig_nodes) {
    const size_t nodes = model_.nodes.size();
    std::vector<char> targeted(nodes, 0);
    for (const tinygltf::Animation& anim : model_.animations)
      for (const tinygltf::AnimationChannel& channel : anim.channels)
        if (channel.target_node >= 0 && size_t(channel.target_node) < nodes && channel.target_path != "weights")
          targeted[size_t(channel.target_node)] = 1;
    // Whether a channel moves the node or one above it, each node's answer kept: every chain is walked once, however
    // many skins' joints share it.
    std::vector<signed char> moved_chain(nodes, -1);
    auto chain_targeted = [&](int n) {
      std::vector<int> walked;
      int up = n;
      for (; up >= 0 && moved_chain[size_t(up)] < 0 && !targeted[size_t(up)]; up = parent[size_t(up)]) walked.push_back(up);
      const signed char answer = up < 0 ? 0 : targeted[size_t(up)] ? 1 : moved_chain[size_t(up)];
      for (int w : walked) moved_chain[size_t(w)] = answer;
      return answer == 1;
    };
    skinned_by_.assign(nodes, {});
    for (const NodeContent& c : content_) {
      const tinygltf::Node& node = model_.nodes[size_t(c.node)];
      std::vector<int> joints;
      if (node.mesh >= 0 && node.skin >= 0 && size_t(node.skin) < model_.skins.size())
        joints = model_.skins[size_t(node.skin)].joints;
      bool moves = chain_targeted(c.node);
      for (int j : joints) moves = moves || (j >= 0 && size_t(j) < nodes && chain_targeted(j));
      if (!moves) continue;
      const size_t index = scene_.movers.size();
      Scene::Mover mover;
      mover.label = node_label(model_, c.node);
      mover.placed = c.world;
      mover.first_triangle = c.first_triangle;
      mover.triangle_count = c.triangle_count;
      mover.light = c.light;
      // The joints' chains: a channel on any of their nodes deforms the mesh (read_animations notes which). Bounded
      // with the rigs' nodes: many skins of many joints under a deep chain must not make the loader walk their product.
      for (int j : joints)
        for (int n = j; n >= 0 && size_t(n) < nodes; n = parent[size_t(n)]) {
          if (++rig_nodes > max_rig_nodes)
            fail("its moving skins' joints and the cameras and moving meshes and lights sit under more than " +
                 std::to_string(max_rig_nodes) + " nodes in all (each one's chain of nodes up to its scene root "
                 "counted)");
          std::vector<size_t>& movers = skinned_by_[size_t(n)];
          if (movers.empty() || movers.back() != index) movers.push_back(index);
        }
      std::vector<int> chain;
      for (int n = c.node; n >= 0; n = parent[size_t(n)]) chain.push_back(n);
      rig_nodes += chain.size();
      if (rig_nodes > max_rig_nodes)
        fail("its cameras and moving meshes and lights sit under more than " + std::to_string(max_rig_nodes) +
             " nodes in all (each one's chain of nodes up to its scene root counted)");
      std::reverse(chain.begin(), chain.end());
      for (int n : chain) {
        in_rigs[size_t(n)].push_back({kMoverRig + index, mover.rig.chain.size()});
        mover.rig.chain.push_back(rig_node(n));
      }
      scene_.movers.push_back(std::move(mover));
    }
  }

  // The cameras' rigs (scene/animation.h) and what each animation moves besides them.
  void read_animations() {
    const size_t nodes = model_.nodes.size();
    std::vector<int> parent(nodes, -1);
    for (size_t n = 0; n < nodes; ++n)
      for (int c : model_.nodes[n].children) parent[size_t(c)] = int(n);
    // A node above a mesh or a light carries it: moving that node moves the scene.
    std::vector<char> carries(nodes, 0);
    auto mark_carriers = [&](int n) {
      for (int a = n; a >= 0 && !carries[size_t(a)]; a = parent[size_t(a)]) carries[size_t(a)] = 1;
    };
    for (size_t n = 0; n < nodes; ++n) {
      const tinygltf::Node& node = model_.nodes[n];
      if (node.mesh < 0 && !node.extensions.count("KHR_lights_punctual")) continue;
      mark_carriers(int(n));
      // A skinned mesh's joints (and the nodes above them) place its vertices: moving them moves the mesh.
      if (node.mesh >= 0 && node.skin >= 0 && size_t(node.skin) < model_.skins.size())
        for (int j : model_.skins[size_t(node.skin)].joints)
          if (j >= 0 && size_t(j) < nodes) mark_carriers(j);
    }
    // Where each node sits in the cameras' chains.
    std::vector<std::vector<std::pair<size_t, size_t>>> in_rigs(nodes);
    scene_.camera_rigs.clear();
    // Every camera keeps its own chain and copies of its channels: bounded, so that many cameras under one deep chain
    // cannot make the loader hold their product (found by thinking like the fuzzer).
    constexpr size_t kMaxRigNodes = 1u << 20, kMaxRigKeyFloats = size_t(1) << 26;
    size_t rig_nodes = 0, rig_key_floats = 0;
    for (int camera_node : camera_nodes_) {
      std::vector<int> chain;
      for (int n = camera_node; n >= 0; n = parent[size_t(n)]) chain.push_back(n);
      rig_nodes += chain.size();
      if (rig_nodes > kMaxRigNodes)
        fail("its cameras sit under more than " + std::to_string(kMaxRigNodes) + " nodes in all (each camera's chain "
             "of nodes up to its scene root counted)");
      std::reverse(chain.begin(), chain.end());
      NodeRig rig;
      for (int n : chain) {
        in_rigs[size_t(n)].push_back({scene_.camera_rigs.size(), rig.chain.size()});
        rig.chain.push_back(rig_node(n));
      }
      scene_.camera_rigs.push_back(std::move(rig));
    }
    read_movers(parent, in_rigs, rig_nodes, kMaxRigNodes);
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& anim = model_.animations[a];
      const std::string name = "animations[" + std::to_string(a) + "] '" + printable(anim.name) + "'";
      scene_.animation_names.push_back(anim.name.empty() ? "animation " + std::to_string(a) : printable(anim.name));
      scene_.animation_durations.push_back(0.0);
      for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = anim.channels[c];
        const int n = channel.target_node;
        if (n < 0 || size_t(n) >= nodes) continue;  // a pointer target (KHR_animation_pointer): not sampled
        const std::string& path = channel.target_path;
        if (carries[size_t(n)]) {
          for (const size_t m : skinned_by_[size_t(n)])
            if (std::find(scene_.movers[m].skin_animations.begin(), scene_.movers[m].skin_animations.end(), int(a)) ==
                scene_.movers[m].skin_animations.end())
              scene_.movers[m].skin_animations.push_back(int(a));
          scene_.animated_content.push_back({int(a),
                                             name + " moves " + node_label(model_, n) +
                                                 (path == "weights" ? "'s morph weights"
                                                                    : ", which holds or carries a mesh or a light"),
                                             path == "weights"});
          // The scene moves as long as its last key: a pose's time runs to it (ScenePose).
          const std::vector<float> times =
              read_floats(anim.samplers[size_t(channel.sampler)].input, 1,
                          name + ".channels[" + std::to_string(c) + "].input");
          if (!times.empty() && std::isfinite(times.back()))
            scene_.animation_durations[a] = std::max(scene_.animation_durations[a], double(times.back()));
        }
        if (in_rigs[size_t(n)].empty() || path == "weights") continue;
        AnimatedProperty property;
        if (path == "translation") property = AnimatedProperty::translation;
        else if (path == "rotation") property = AnimatedProperty::rotation;
        else if (path == "scale") property = AnimatedProperty::scale;
        else continue;
        const std::string where = name + ".channels[" + std::to_string(c) + "]";
        if (model_.nodes[size_t(n)].matrix.size() == 16)
          fail(where + " animates " + node_label(model_, n) + ", which has a matrix (glTF animates nodes given by "
               "translation, rotation and scale only)");
        const AnimationTrack track = read_track(int(a), anim.samplers[size_t(channel.sampler)], property,
                                                where + " (sampler " + std::to_string(channel.sampler) + ")");
        rig_key_floats += (track.times.size() + track.values.size()) * in_rigs[size_t(n)].size();
        if (rig_key_floats > kMaxRigKeyFloats)
          fail(where + ": the animation keys of the cameras and the moving meshes and lights pass " +
               std::to_string(kMaxRigKeyFloats) + " numbers in all (each holds the keys of the nodes above it)");
        for (const auto& [rig, position] : in_rigs[size_t(n)])
          (rig < kMoverRig ? scene_.camera_rigs[rig] : scene_.movers[rig - kMoverRig].rig)
              .chain[position]
              .tracks.push_back(track);
        scene_.animation_durations[a] = std::max(scene_.animation_durations[a], double(track.times.back()));
      }
    }
  }

  std::string path_;
  const tinygltf::Model& model_;
  Scene& scene_;
  const SceneLimits& limits_;
  HostBudget& budget_;
  const std::set<int>& zero_accessors_;  // no buffer view in the file: zeros (CheckedGltf::zero_accessors)
  ScenePose pose_;
  std::map<int, glm::mat4> posed_;  // the nodes the pose's animation moves, their local transforms at its time
  std::vector<int> texture_slots_;
  int default_material_ = -1;
  std::vector<std::optional<glm::mat4>> node_world_;
  std::vector<int> parent_;
  std::vector<int> camera_nodes_;  // the node of each camera added, in the order of scene_.cameras
  // What each node that holds a mesh or a light placed, in the order visited: the movers (Scene::movers) among them.
  struct NodeContent {
    int node;
    glm::mat4 world;
    size_t first_triangle, triangle_count;
    int light;
  };
  std::vector<NodeContent> content_;
  std::vector<std::vector<size_t>> skinned_by_;  // for each node, the movers whose skin a channel on it deforms
};

}  // namespace

namespace {

// What tinygltf's callbacks need: the files check_gltf allowed, and the first refusal, which replaces tinygltf's own
// words in the message.
struct LoadContext {
  const CheckedGltf* checked;
  const AssetAccess* access;
  const SceneLimits* limits;
  HostBudget* budget;
  std::string refusal;
};

std::string no_expansion(const std::string& path, void*) { return path; }

// tinygltf asks for a file by its base directory joined to a URI, then again relative to the working directory:
// only the paths check_gltf resolved exist for it.
bool allowed_file_exists(const std::string& path, void* user) {
  const LoadContext& context = *static_cast<LoadContext*>(user);
  return context.checked->files.count(path) > 0;
}

bool read_allowed_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  LoadContext& context = *static_cast<LoadContext*>(user);
  auto it = context.checked->files.find(path);
  if (it == context.checked->files.end()) {
    if (err) *err += "refused\n";
    return false;
  }
  try {
    *out = context.access->read(it->second.file, it->second.bytes, it->second.what);
  } catch (const Error& e) {
    if (context.refusal.empty()) context.refusal = e.what();
    return false;
  }
  return true;
}

bool write_nothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// tinygltf's image decoder, with the size read from the image's header and charged to the host budget before any
// pixel is decoded. Every image becomes 8 bits a channel (rcsplat's textures are RGBA8).
bool decode_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                  const unsigned char* bytes, int size, void* user) {
  LoadContext& context = *static_cast<LoadContext*>(user);
  const std::string object = "images[" + std::to_string(index) + "]" +
                             (!image->uri.empty()    ? " '" + image->uri.substr(0, 80) + "'"
                              : !image->name.empty() ? " '" + image->name + "'"
                                                     : "");
  const std::string name = context.access->scene_file() + ": " + object;
  auto refuse = [&](const std::string& what) {
    if (context.refusal.empty()) context.refusal = name + ": " + what;
    if (err) *err += "refused\n";
    return false;
  };
  int width = 0, height = 0, channels = 0;
  const bool webp = size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0;
  if (webp) {
    // EXT_texture_webp: libwebp reads the size from the header, then decodes to RGBA.
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(bytes, size_t(size), &features) != VP8_STATUS_OK) return refuse("its WebP header is damaged");
    width = features.width;
    height = features.height;
    channels = 4;
  } else if (!stbi_info_from_memory(bytes, size, &width, &height, &channels)) {
    // The decoder refuses a header whose pixels would pass 1 GiB before saying its size: read a PNG's here.
    if (size >= 24 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0) {
      auto big_endian = [&](int at) { return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3]; };
      const uint32_t w = big_endian(16), h = big_endian(20);
      if (w > uint32_t(context.limits->max_texture_side) || h > uint32_t(context.limits->max_texture_side))
        return refuse("is " + std::to_string(w) + " x " + std::to_string(h) + " pixels; rcsplat reads textures of at most " +
                      std::to_string(context.limits->max_texture_side) + " pixels a side");
    }
    return refuse("not an image rcsplat reads (PNG, JPEG, WebP, BMP, GIF, TGA, PSD, HDR, PNM), or its header is damaged");
  }
  const int side = context.limits->max_texture_side;
  if (width <= 0 || height <= 0 || width > side || height > side)
    return refuse("is " + std::to_string(width) + " x " + std::to_string(height) + " pixels; rcsplat reads textures of at most " +
                  std::to_string(side) + " pixels a side");
  const uint64_t pixels = uint64_t(width) * uint64_t(height);
  try {
    context.budget->charge(pixels * (uint64_t(channels) + 4), object + " (decoded)");
  } catch (const Error& e) {
    if (context.refusal.empty()) context.refusal = e.what();
    return false;
  }
  if (webp) {
    image->image.resize(pixels * 4);
    if (!WebPDecodeRGBAInto(bytes, size_t(size), image->image.data(), image->image.size(), width * 4)) {
      image->image.clear();
      return refuse("its WebP pixel data is damaged or truncated (" + std::to_string(width) + " x " +
                    std::to_string(height) + " in its header)");
    }
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    return true;
  }
  int w = 0, h = 0, n = 0;
  unsigned char* decoded = stbi_load_from_memory(bytes, size, &w, &h, &n, 0);
  if (!decoded || w != width || h != height || n != channels) {
    if (decoded) stbi_image_free(decoded);
    return refuse("its pixel data is damaged or truncated (" + std::to_string(width) + " x " + std::to_string(height) +
                  " in its header)");
  }
  image->width = w;
  image->height = h;
  image->component = n;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(decoded, decoded + pixels * uint64_t(n));
  stbi_image_free(decoded);
  return true;
}

}  // namespace

Scene load_gltf(const std::string& path, const SceneLimits& limits, const ScenePose& pose) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path + ": no such file");
  const AssetAccess access(path, limits.asset_roots);
  HostBudget budget(path, limits);
  const CheckedGltf checked = check_gltf(access, limits, budget);
  LoadContext context{&checked, &access, &limits, &budget, {}};
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&allowed_file_exists, &no_expansion, &read_allowed_file, &write_nothing, &context});
  loader.SetImageLoader(&decode_image, &context);
  std::string err, warn;
  bool ok;
  try {
    const std::string base = checked.base_dir;
    ok = checked.binary
             ? loader.LoadBinaryFromMemory(&model, &err, &warn, checked.bytes.data(), unsigned(checked.bytes.size()), base)
             : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(checked.bytes.data()),
                                          unsigned(checked.bytes.size()), base);
  } catch (const std::exception& e) {
    throw Error(path + ": cannot be parsed (" + (context.refusal.empty() ? "the glTF parser stopped" : context.refusal) + ")");
  }
  if (!context.refusal.empty()) throw Error(context.refusal);
  if (!ok) {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    throw Error(path + ": cannot be loaded: " +
                (err.empty() ? "the glTF parser refused it without naming the defect, after rcsplat's own checks "
                               "passed; please report it with the file (docs/SECURITY.md)"
                             : err));
  }
  if (!warn.empty()) {
    while (!warn.empty() && warn.back() == '\n') warn.pop_back();
    log_warning(path + ": " + warn);
  }
  Scene scene;
  scene.source = path;
  // Every coordinate is finite, but their spread must be too: cameras, lights and the device frame are derived
  // from the bounding box (found by fuzzing: a misaligned view read floats near 1e38, or 1e-38).
  GltfReader(path, model, scene, limits, budget, checked.zero_accessors, pose).read();
  scene.check_extent();
  return scene;
}

}  // namespace rcsplat
