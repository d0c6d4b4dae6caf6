// A scene as rcsplat renders it: world-space triangles (unindexed), their materials and textures, lights, a camera.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "scene/animation.h"
#include "scene/environment.h"

namespace rcsplat {

struct SceneMaterial {
  std::string name;
  glm::vec4 base_color{1.0f};  // linear
  int base_color_texture = -1;
  glm::vec3 emission{0.0f};  // emissiveFactor x strength: linear radiance
  bool double_sided = false;
  float alpha_cutoff = 0.0f;  // glTF alpha mode MASK: where alpha is below it the surface is a hole; 0: opaque
  bool alpha_blend = false;   // glTF alpha mode BLEND: a point is seen with probability alpha (hashed transparency)
  // The BRDF (kernels/brdf.h). A scene built in code is Lambertian unless it says otherwise; the glTF loader sets
  // glTF's defaults (metallic 1, roughness 1, specular 1).
  float metallic = 0.0f;
  float roughness = 1.0f;
  float specular = 0.0f;  // KHR_materials_specular's specularFactor: the dielectric's specular layer
  int metallic_roughness_texture = -1;  // B: metallic, G: roughness (linear), times the factors
  int specular_texture = -1;  // KHR_materials_specular's specularTexture: its A (linear) times specular
  int emissive_texture = -1;  // glTF's emissiveTexture (sRGB): multiplies emission; its triangles need uvs
  // glTF's normalTexture (linear, tangent space: x, y, z = 2 rgb - 1) and its scale (multiplies x and y); its
  // triangles need uvs and Scene::tangents.
  int normal_texture = -1;
  float normal_scale = 1.0f;
  // Glass (kernels/glass.h): KHR_materials_transmission (factor, and a texture whose R multiplies it), KHR_materials_ior
  // and KHR_materials_volume (thickness 0: thin-walled; above 0 rays refract into the mesh's volume, attenuated by
  // attenuation_color at attenuation_distance, infinite: clear).
  float transmission = 0.0f;
  int transmission_texture = -1;
  float ior = 1.5f;
  float thickness = 0.0f;
  glm::vec3 attenuation_color{1.0f};
  float attenuation_distance = std::numeric_limits<float>::infinity();
  // Layers (kernels/brdf_layers.h): KHR_materials_specular's colour (the dielectric's F0 tint) and its texture (sRGB,
  // RGB); KHR_materials_clearcoat (weight and texture R, roughness and texture G, normal texture and its scale; the
  // textures share the base colour's mapping); KHR_materials_sheen (colour and texture sRGB RGB, roughness and texture A).
  glm::vec3 specular_color{1.0f};
  int specular_color_texture = -1;
  float clearcoat = 0.0f;
  int clearcoat_texture = -1;
  float clearcoat_roughness = 0.0f;
  int clearcoat_roughness_texture = -1;
  int clearcoat_normal_texture = -1;
  float clearcoat_normal_scale = 1.0f;
  glm::vec3 sheen_color{0.0f};
  int sheen_color_texture = -1;
  float sheen_roughness = 0.0f;
  int sheen_roughness_texture = -1;
  // Whether a layer changes the BRDF: a coat, a sheen, or a specular colour that is not white on a specular layer.
  bool layered() const {
    const bool tinted = (specular_color != glm::vec3(1.0f) || specular_color_texture >= 0) && specular > 0.0f &&
                        metallic < 1.0f;
    return clearcoat > 0.0f || (sheen_color.x > 0.0f || sheen_color.y > 0.0f || sheen_color.z > 0.0f) || tinted;
  }
};

struct SceneTexture {
  std::string name;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // sRGB-encoded RGBA8, rows top to bottom
  int wrap_s = 0, wrap_t = 0;  // WRAP_REPEAT, WRAP_CLAMP or WRAP_MIRROR (shared_types.h)
  bool nearest = false;        // the sampler's NEAREST magnification filter: no bilinear interpolation
  // Minified by its footprint through a mip chain (trilinear), unless the sampler's minFilter is plain NEAREST or
  // LINEAR: glTF leaves an absent minFilter to the renderer, and rcsplat filters.
  bool mipmaps = true;
};

enum class LightType { point, spot, directional };

struct SceneLight {
  std::string name;
  LightType type = LightType::point;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the direction light travels
  glm::vec3 intensity{1.0f};             // colour x intensity (cd, or lux for directional)
  float range = 0.0f;                    // 0 = infinite
  float inner_cone = 0.0f, outer_cone = 0.7853982f;
};

struct SceneCamera {
  std::string name;
  bool orthographic = false;
  glm::vec3 eye{0.0f}, target{0.0f, 0.0f, -1.0f}, up{0.0f, 1.0f, 0.0f};
  float yfov = 0.8f;               // radians (perspective)
  float xmag = 1.0f, ymag = 1.0f;  // half width and half height of the view in world units (orthographic)
  std::optional<float> aspect;     // width / height, if the scene states one
};

struct Scene {
  std::string source;  // file it came from, or "built-in Cornell box"
  std::vector<glm::vec3> positions;  // three per triangle
  std::vector<glm::vec3> normals;    // three per triangle (unit)
  std::vector<glm::vec2> uvs;        // three per triangle
  std::vector<glm::vec3> colors;     // three per triangle: vertex colour (glTF COLOR_0), linear, multiplies the base colour
  // Three per triangle, or empty when no material has a normal map: the tangent (xyz, unit, along +u) and in w the
  // bitangent's sign (glTF TANGENT: bitangent = cross(normal, tangent) * w). A zero tangent: the kernels make a frame.
  std::vector<glm::vec4> tangents;
  std::vector<uint32_t> triangle_material;
  std::vector<SceneMaterial> materials;
  std::vector<SceneTexture> textures;
  std::vector<SceneLight> lights;
  std::vector<SceneCamera> cameras;
  // glTF animation (scene/animation.h): the rig of each glTF camera (same order as `cameras`; a camera added for a
  // scene without one has none), the animations' names, and what each animation moves that is not a camera: a node
  // that holds or carries a mesh or a light, or a mesh's morph weights ("animations[0] 'Open' moves nodes[4] 'Door'").
  std::vector<NodeRig> camera_rigs;
  std::vector<std::string> animation_names;
  struct AnimatedContent {
    int animation = 0;
    std::string what;
    bool morph_weights = false;  // what it animates is morph weights, which no pose plays (ScenePose)
  };
  std::vector<AnimatedContent> animated_content;
  std::vector<double> animation_durations;  // each animation's last key time over all its channels, seconds
  // Every node that holds a mesh or a light and that some animation moves (a channel on it or on a node above it, or
  // for a skinned mesh on a joint), with what it placed: scene/scene_animator.h poses them at any time.
  struct Mover {
    std::string label;       // "nodes[4] 'Ball'"
    NodeRig rig;             // from its scene root down to the node
    glm::mat4 placed{1.0f};  // the node's world transform in the pose the loader read (posed_animation, posed_time)
    size_t first_triangle = 0, triangle_count = 0;  // its mesh's triangles (none: 0)
    int light = -1;                                 // its light's index in `lights`, or -1
    // Placed by its skin's joints, not by its node: an animation of the joints deforms it, which no rigid move
    // follows (`animate` loads such a scene again for each frame: --cache-per-frame).
    std::vector<int> skin_animations;
  };
  std::vector<Mover> movers;
  // The pose the loader placed the scene in (ScenePose): -1, the rest pose.
  int posed_animation = -1;
  double posed_time = 0.0;
  // Light from outside (--sky, --environment); none by default: rays that leave the scene see black.
  Environment environment;
  GlassLight glass_light;  // --light-through-glass and its photons (scene/environment.h)
  // What the file asks for that rcsplat does not simulate, once each, as "feature: what rcsplat does instead".
  std::vector<std::string> unsupported;

  size_t triangle_count() const { return triangle_material.size(); }
  bool has_emissive_triangles() const;
  bool has_vertex_colors() const;  // some vertex colour is not white
  glm::vec3 bounds_min() const;
  glm::vec3 bounds_max() const;

  // Appends a triangle; normals default to the geometric normal, texture coordinates to zero.
  void add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint32_t material);
  // A planar quadrilateral a-b-c-d (counter-clockwise seen from the side its normal points to) as the triangles
  // a-b-c and a-c-d.
  void add_quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d, uint32_t material);

  float bounding_radius() const;
  // Throws rcsplat::Error (naming source) unless the bounding radius lies in [1e-15, 1e15] units (or is 0: one point):
  // point-light intensities scale with the square of the unit, and beyond that range their squares leave single
  // precision (found by fuzzing). A femtometre to 6700 astronomical units covers every scene in metres.
  void check_extent() const;
  // What a scene without a camera or light gets (render/camera.h add_view_defaults adds them, with a warning): a
  // camera looking at the centre along -z, and a point light a scene radius above the camera actually used.
  SceneCamera default_camera() const;
  SceneLight default_light(const SceneCamera& view) const;
};

}  // namespace rcsplat
