#include "scene/packed_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "util/colour.h"

namespace rcsplat {
namespace {

void put3(float* dst, const glm::vec3& v) {
  dst[0] = v.x;
  dst[1] = v.y;
  dst[2] = v.z;
}

}  // namespace

uint32_t pack_vertex_color(const glm::vec3& c) {
  uint32_t packed = 0;
  for (int k = 0; k < 3; ++k) {
    float v = std::isfinite(c[k]) ? std::clamp(c[k], 0.0f, 1.0f) : 1.0f;
    packed |= uint32_t(std::lround(v * VERTEX_COLOR_MAX)) << (VERTEX_COLOR_BITS * k);
  }
  return packed;
}

glm::vec3 unpack_vertex_color(uint32_t packed) {
  glm::vec3 c;
  for (int k = 0; k < 3; ++k) c[k] = float((packed >> (VERTEX_COLOR_BITS * k)) & VERTEX_COLOR_MAX) / float(VERTEX_COLOR_MAX);
  return c;
}

namespace {

PunctualLight pack_light(const SceneLight& l) {
  PunctualLight out{};
  put3(out.position, l.position);
  put3(out.direction, glm::normalize(l.direction));
  put3(out.intensity, l.intensity);
  out.range = l.range > 0.0f ? l.range : 0.0f;
  out.type = l.type == LightType::point ? LIGHT_POINT : l.type == LightType::spot ? LIGHT_SPOT : LIGHT_DIRECTIONAL;
  // glTF's recommended spot falloff: saturate(cos(angle) * scale + offset)^2.
  float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
  out.spot_scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
  out.spot_offset = -cos_outer * out.spot_scale;
  return out;
}

// The emitted luminance of material m averaged over triangle t: its factor's, times its texture's mean over the
// triangle where it has one. Texels are read at 16 to 64 stratified points (enough to weigh emitters against one
// another: an estimate only moves the light sampler's choice, never its result), nearest, so the work is bounded.
double mean_emitted_luminance(const Scene& scene, size_t t, const SceneMaterial& m) {
  const glm::vec3 factor = m.emission;
  if (m.emissive_texture < 0 || size_t(m.emissive_texture) >= scene.textures.size())
    return luminance_f(factor.x, factor.y, factor.z);
  const SceneTexture& tex = scene.textures[size_t(m.emissive_texture)];
  const glm::vec2 uv0 = scene.uvs[3 * t], e1 = scene.uvs[3 * t + 1] - uv0, e2 = scene.uvs[3 * t + 2] - uv0;
  // Texels the triangle covers, for how many points to read (4^2 to 8^2: a few a texel edge it may cross).
  constexpr int kMinSide = 4, kMaxSide = 8;
  const double texels = 0.5 * std::fabs(double(e1.x) * e2.y - double(e1.y) * e2.x) * tex.width * tex.height;
  const int side = std::clamp(int(std::ceil(4.0 * std::sqrt(std::min(texels, 1e4)))), kMinSide, kMaxSide);
  auto wrap = [](long i, long n, int mode) {
    if (mode == WRAP_CLAMP) return std::clamp(i, 0L, n - 1);
    long m2 = ((i % (2 * n)) + 2 * n) % (2 * n);
    if (mode == WRAP_MIRROR) return m2 < n ? m2 : 2 * n - 1 - m2;
    return ((i % n) + n) % n;
  };
  double sum = 0.0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      // The centre of stratum (i, j) of the unit square, taken onto the triangle as the light sampler does.
      double su = std::sqrt((i + 0.5) / side), v = (j + 0.5) / side;
      glm::dvec2 uv = glm::dvec2(uv0) + su * (1.0 - v) * glm::dvec2(e1) + su * v * glm::dvec2(e2);
      double fx = std::floor(uv.x * tex.width), fy = std::floor(uv.y * tex.height);
      if (!std::isfinite(fx) || !std::isfinite(fy) || std::fabs(fx) > 1e8 || std::fabs(fy) > 1e8) fx = fy = 0.0;
      size_t x = size_t(wrap(long(fx), tex.width, tex.wrap_s)), y = size_t(wrap(long(fy), tex.height, tex.wrap_t));
      const uint8_t* texel = &tex.rgba[4 * (y * size_t(tex.width) + x)];
      sum += luminance(factor.x * srgb_to_linear(texel[0] / 255.0), factor.y * srgb_to_linear(texel[1] / 255.0),
                       factor.z * srgb_to_linear(texel[2] / 255.0));
    }
  return sum / (side * side);
}

// The next mip level of a w x h RGBA8 level: each texel the mean of the 2 x 2 block above it (the block's last row or
// column repeated where a side is odd), colour decoded from sRGB and encoded again where `srgb`, alpha and data
// textures (normal and metallic-roughness maps) averaged as stored.
std::vector<uint8_t> next_mip_level(const uint8_t* level, uint32_t w, uint32_t h, bool srgb) {
  const uint32_t nw = texture_level_side(w, 1), nh = texture_level_side(h, 1);
  std::vector<uint8_t> out(size_t(nw) * nh * 4);
  auto encode = [](double linear) { return uint8_t(std::lround(linear_to_srgb(std::clamp(linear, 0.0, 1.0)) * 255.0)); };
  for (uint32_t y = 0; y < nh; ++y)
    for (uint32_t x = 0; x < nw; ++x)
      for (int c = 0; c < 4; ++c) {
        double sum = 0.0;
        for (uint32_t dy = 0; dy < 2; ++dy)
          for (uint32_t dx = 0; dx < 2; ++dx) {
            const uint32_t sx = std::min(2 * x + dx, w - 1), sy = std::min(2 * y + dy, h - 1);
            const double v = level[(size_t(sy) * w + sx) * 4 + size_t(c)] / 255.0;
            sum += srgb && c < 3 ? srgb_to_linear(v) : v;
          }
        out[(size_t(y) * nw + x) * 4 + size_t(c)] = srgb && c < 3 ? encode(0.25 * sum) : uint8_t(std::lround(0.25 * sum * 255.0));
      }
  return out;
}

// Appends texture t's texels, level 0 then (with mipmaps) each smaller level down to 1 x 1, and returns its levels.
uint32_t append_texels(const SceneTexture& t, bool srgb, std::vector<uint32_t>& texels) {
  std::vector<uint8_t> level = t.rgba;
  uint32_t w = uint32_t(t.width), h = uint32_t(t.height), levels = 1;
  for (;;) {
    const size_t start = texels.size();
    texels.resize(start + level.size() / 4);
    std::memcpy(texels.data() + start, level.data(), level.size());
    if (!t.mipmaps || (w == 1 && h == 1)) return levels;
    level = next_mip_level(level.data(), w, h, srgb);
    w = texture_level_side(w, 1);
    h = texture_level_side(h, 1);
    ++levels;
  }
}

}  // namespace

// The material's layers (kernels/brdf_layers.h) into `out`, and the lobe kind they make (layered_lobe): a texture can
// only lower a factor, so a roughness texture classifies the coat at roughness 0, its sharpest. Glass keeps no layers
// (the loader names that).
static void pack_layers(const SceneMaterial& m, Material& out) {
  put3(out.specular_color, glm::max(m.specular_color, glm::vec3(0.0f)));
  out.specular_color_texture = m.specular_color_texture;
  out.clearcoat = std::clamp(m.clearcoat, 0.0f, 1.0f);
  out.clearcoat_texture = m.clearcoat_texture;
  out.clearcoat_roughness = std::clamp(m.clearcoat_roughness, 0.0f, 1.0f);
  out.clearcoat_roughness_texture = m.clearcoat_roughness_texture;
  out.clearcoat_normal_texture = m.clearcoat_normal_texture;
  out.clearcoat_normal_scale = std::isfinite(m.clearcoat_normal_scale) ? m.clearcoat_normal_scale : 1.0f;
  put3(out.sheen_color, glm::clamp(m.sheen_color, glm::vec3(0.0f), glm::vec3(1.0f)));
  out.sheen_color_texture = m.sheen_color_texture;
  out.sheen_roughness = std::clamp(m.sheen_roughness, 0.0f, 1.0f);
  out.sheen_roughness_texture = m.sheen_roughness_texture;
  out.layered = m.layered() && m.transmission == 0.0f ? 1 : 0;
  if (!out.layered) return;
  const float sheen = std::max({out.sheen_color[0], out.sheen_color[1], out.sheen_color[2]});
  const float coat_roughness = out.clearcoat_roughness_texture >= 0 ? 0.0f : out.clearcoat_roughness;
  out.lobe = layered_lobe(out.lobe, out.clearcoat, coat_roughness, sheen);
}

TriangleShading pack_triangle(const Scene& scene, const SceneFrame& frame, size_t t, float* twice_area_out) {
  TriangleShading s;
  std::memset(&s, 0, sizeof s);
  const glm::vec3 v[3] = {frame.to_device(scene.positions[3 * t]), frame.to_device(scene.positions[3 * t + 1]),
                          frame.to_device(scene.positions[3 * t + 2])};
  glm::vec3 ng = glm::cross(v[1] - v[0], v[2] - v[0]);
  const float twice_area = glm::length(ng);
  ng = twice_area > 0.0f ? ng / twice_area : glm::vec3(0, 0, 1);
  put3(s.geometric_normal, ng);
  put3(s.v0, v[0]);
  put3(s.v1, v[1]);
  put3(s.v2, v[2]);
  s.material = scene.triangle_material[t];
  s.emitter = -1;
  put3(s.normal0, scene.normals[3 * t]);
  put3(s.normal1, scene.normals[3 * t + 1]);
  put3(s.normal2, scene.normals[3 * t + 2]);
  for (int k = 0; k < 3; ++k) s.color[k] = pack_vertex_color(scene.colors.empty() ? glm::vec3(1.0f) : scene.colors[3 * t + size_t(k)]);
  for (int k = 0; k < 2; ++k) {
    s.uv0[k] = scene.uvs[3 * t][k];
    s.uv1[k] = scene.uvs[3 * t + 1][k];
    s.uv2[k] = scene.uvs[3 * t + 2][k];
  }
  if (twice_area_out) *twice_area_out = twice_area;
  return s;
}

bool emits(const Scene& scene, size_t t) {
  const glm::vec3& e = scene.materials[scene.triangle_material[t]].emission;
  return luminance_f(e.x, e.y, e.z) > 0.0f;
}

void place_emitter(const TriangleShading& s, float twice_area, EmissiveTriangle& e) {
  const glm::vec3 v0(s.v0[0], s.v0[1], s.v0[2]), v1(s.v1[0], s.v1[1], s.v1[2]), v2(s.v2[0], s.v2[1], s.v2[2]);
  put3(e.v0, v0);
  put3(e.edge1, v1 - v0);
  put3(e.edge2, v2 - v0);
  e.area = 0.5f * twice_area;
}

void select_emitters(std::vector<EmissiveTriangle>& emitters, const std::vector<double>& emitter_power,
                     const std::vector<double>& emitter_area) {
  // Emitters are chosen half in proportion to their power and half to their area: power alone starves a room whose
  // lights are a million times dimmer than another room's of all samples (HardCases.RoomsAMillionTimesApartInOneFrame:
  // its light vanished); the area half bounds the variance any emitter can cause by a factor 2 over power alone.
  double total_power = 0.0, total_area = 0.0, running = 0.0;
  for (size_t i = 0; i < emitters.size(); ++i) {
    total_power += emitter_power[i];
    total_area += emitter_area[i];
  }
  for (size_t i = 0; i < emitters.size(); ++i) {
    // A textured emitter may be black all over (its texture's mean is 0): then area alone chooses.
    double select = total_power > 0.0 ? 0.5 * emitter_power[i] / total_power + 0.5 * emitter_area[i] / total_area
                                       : emitter_area[i] / total_area;
    running += select;
    emitters[i].pdf_select = float(select);
    emitters[i].cdf = float(running);
  }
  if (!emitters.empty()) emitters.back().cdf = 1.0f;  // no sample may fall past the last entry through rounding
}

std::vector<PunctualLight> pack_lights(const Scene& scene, const SceneFrame& frame) {
  std::vector<PunctualLight> lights;
  for (const SceneLight& l : scene.lights) lights.push_back(pack_light(frame.device_light(l)));
  return lights;
}

PackedScene pack_scene(const Scene& scene, const SceneFrame& frame, Texels texels) {
  PackedScene p;
  size_t n = scene.triangle_count();
  p.triangles.resize(n);
  for (size_t t = 0; t < n; ++t) {
    float twice_area = 0.0f;
    TriangleShading& s = p.triangles[t];
    s = pack_triangle(scene, frame, t, &twice_area);
    const SceneMaterial& m = scene.materials[s.material];
    if (emits(scene, t) && twice_area > 0.0f) {
      const double emitted = mean_emitted_luminance(scene, t, m);
      EmissiveTriangle e{};
      place_emitter(s, twice_area, e);
      put3(e.radiance, m.emission);
      const bool textured = m.emissive_texture >= 0 && size_t(m.emissive_texture) < scene.textures.size();
      e.sides_and_texture = (m.double_sided ? 1 : 0) | (textured ? int(t) + 1 : 0) << 1;
      p.emitter_mean_luminance.push_back(float(emitted));
      p.emitter_emitted.push_back(emitted);
      p.emitter_triangle.push_back(uint32_t(t));
      const double sides = m.double_sided ? 2.0 : 1.0;
      p.emitter_power.push_back(emitted * e.area * sides);
      p.emitter_area.push_back(double(e.area) * sides);
      s.emitter = int(p.emitters.size());
      p.emitters.push_back(e);
    }
  }
  select_emitters(p.emitters, p.emitter_power, p.emitter_area);

  for (const SceneMaterial& m : scene.materials) {
    Material out{};
    for (int i = 0; i < 4; ++i) out.base_color[i] = m.base_color[i];
    put3(out.emission, m.emission);
    out.base_color_texture = m.base_color_texture;
    out.double_sided = m.double_sided ? 1 : 0;
    out.alpha_cutoff = m.alpha_cutoff;
    out.alpha_blend = m.alpha_blend ? 1 : 0;
    out.metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    out.roughness = std::clamp(m.roughness, 0.0f, 1.0f);
    out.specular = std::clamp(m.specular, 0.0f, 1.0f);
    out.metallic_roughness_texture = m.metallic_roughness_texture;
    out.specular_texture = m.specular_texture;
    out.emissive_texture = m.emissive_texture;
    out.normal_texture = m.normal_texture;
    out.normal_scale = std::isfinite(m.normal_scale) ? m.normal_scale : 1.0f;
    out.transmission = std::clamp(m.transmission, 0.0f, 1.0f);
    out.transmission_texture = out.transmission > 0.0f ? m.transmission_texture : TEXTURE_NONE;
    out.ior = std::isfinite(m.ior) && m.ior >= 1.0f ? m.ior : 1.5f;
    out.thickness = std::isfinite(m.thickness) && m.thickness > 0.0f ? m.thickness : 0.0f;
    for (int i = 0; i < 3; ++i) {
      // Beer-Lambert: a colour c left after distance d is exp(-sigma d) = c.
      const float c = std::clamp(m.attenuation_color[i], 1e-6f, 1.0f), d = m.attenuation_distance;
      // Per device unit: the device traces in the frame's units (scene/scene_frame.h).
      out.attenuation[i] = std::isfinite(d) && d > 0.0f ? float(-std::log(double(c)) / double(d) * frame.scale) : 0.0f;
    }
    out.lobe = material_lobe(out.metallic, out.roughness, out.specular);
    // A texture can only lower the factors: the material's lobe is the sharpest its texels may make.
    // (A specular texture can only lower the weight: the factor's lobe stands.)
    if (out.lobe != LOBE_NONE && m.metallic_roughness_texture >= 0) out.lobe = material_lobe(out.metallic, 0.0f, out.specular);
    // Glass all over is never a pixel's or a hit's surface (kernels/glass.h): its reflection is the glass code's, and
    // it needs no BRDF.
    if (out.transmission >= 1.0f && out.transmission_texture < 0 && out.metallic == 0.0f) out.lobe = LOBE_NONE;
    pack_layers(m, out);
    p.materials.push_back(out);
  }
  // Colour textures (base colour, emission) are averaged in linear light down their mip chain; data ones as stored.
  std::vector<bool> colour(scene.textures.size(), false);
  for (const SceneMaterial& m : scene.materials)
    for (int t : {m.base_color_texture, m.emissive_texture, m.specular_color_texture, m.sheen_color_texture})
      if (t >= 0 && size_t(t) < colour.size()) colour[size_t(t)] = true;
  for (size_t i = 0; texels == Texels::packed && i < scene.textures.size(); ++i) {
    const SceneTexture& t = scene.textures[i];
    TextureInfo info{};
    info.first_texel = uint32_t(p.texels.size());
    info.width = uint32_t(t.width);
    info.height = uint32_t(t.height);
    const uint32_t levels = append_texels(t, colour[i], p.texels);
    info.wrap = texture_wrap(uint32_t(t.wrap_s), uint32_t(t.wrap_t), t.nearest, levels);
    p.textures.push_back(info);
  }
  if (scene.tangents.size() == 3 * n) {
    p.tangents.reserve(4 * scene.tangents.size());
    for (const glm::vec4& t : scene.tangents) p.tangents.insert(p.tangents.end(), {t.x, t.y, t.z, t.w});
  }
  p.lights = pack_lights(scene, frame);
  p.glass_caustics = scene.glass_light.caustics;
  p.environment = pack_environment(scene.environment);  // directions: the frame only translates and scales
  return p;
}

}  // namespace rcsplat
