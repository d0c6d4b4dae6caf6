// Issue 41 item 3, measured on a real scene: how bright rcsplat renders the rough dielectrics (metallic 0, roughness
// at least 0.5, a specular layer) of a glTF scene lit by one point light, against glTF's appendix-B model. Renders the
// direct light at pixel centres, then for every such pixel rescales it by the ratio of appendix B's BRDF to rcsplat's
// for the pixel's view and light directions (tests/brdf_reference.h, in double): the shadows and the light's falloff
// are the render's, only the BRDF differs. Prints the summed brightness of appendix B's image and of the old weight
// 1 - F(n.v)'s against rcsplat's. Materials with a metallic-roughness texture are left out (the factors alone do not
// say their roughness).
//   build/benchmarks/dielectric_brightness SCENE.gltf [WIDTH HEIGHT]
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "brdf_reference.h"
#include "cl/device_info.h"
#include "cl/gpu_context.h"
#include "render/renderer.h"
#include "scene/gltf_loader.h"

using namespace rcsplat;
namespace ref = rcsplat::brdf_reference;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE.gltf [WIDTH HEIGHT]\n", argv[0]);
    return 2;
  }
  const Scene scene = load_gltf(argv[1]);
  if (scene.lights.size() != 1 || scene.lights[0].type != LightType::point || scene.cameras.empty()) {
    std::fprintf(stderr, "%s: needs one point light and a camera\n", argv[1]);
    return 1;
  }
  GpuContext gpu(select_device(""));
  Renderer renderer(gpu, scene);
  RenderSettings settings;
  settings.gi = GiMethod::none;
  settings.bounces = 1;
  settings.pixel_samples = 1;
  settings.width = argc > 3 ? std::stoi(argv[2]) : 512;
  settings.height = argc > 3 ? std::stoi(argv[3]) : 384;
  const RenderedImage img = renderer.render(settings);
  const glm::dvec3 eye(scene.cameras[0].eye), light(scene.lights[0].position);

  // rcsplat's weight needs the lobe's albedo by quadrature: kept per roughness and view cosine (to 1/4096).
  std::map<std::pair<float, int>, double> lobe_albedo;
  auto ours_weight_albedo = [&](float roughness, double cos_o) {
    int key = int(std::lround(cos_o * 4096.0));
    auto [it, added] = lobe_albedo.try_emplace({roughness, key}, 0.0);
    if (added) it->second = ref::dielectric_lobe_albedo(key / 4096.0, std::max(double(roughness) * roughness, 1e-3));
    return it->second;
  };
  double rendered = 0.0, appendix_b = 0.0, view_fresnel = 0.0;
  size_t pixels = 0;
  for (size_t i = 0; i < img.triangle.size(); ++i) {
    if (img.triangle[i] < 0) continue;
    const SceneMaterial& material = scene.materials[scene.triangle_material[size_t(img.triangle[i])]];
    if (material.metallic > 0.0f || material.specular <= 0.0f || material.roughness < 0.5f ||
        material.metallic_roughness_texture >= 0)
      continue;
    glm::dvec3 p(img.position[3 * i], img.position[3 * i + 1], img.position[3 * i + 2]);
    glm::dvec3 n = glm::normalize(glm::dvec3(img.normal[3 * i], img.normal[3 * i + 1], img.normal[3 * i + 2]));
    glm::dvec3 t = glm::normalize(glm::cross(n, std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    glm::dvec3 b = glm::cross(n, t), v = glm::normalize(eye - p), l = glm::normalize(light - p);
    ref::Vec wo{glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)}, wi{glm::dot(l, t), glm::dot(l, b), glm::dot(l, n)};
    if (wo.z <= 0.0 || wi.z <= 0.0) continue;
    ref::Material m{{img.albedo[3 * i], img.albedo[3 * i + 1], img.albedo[3 * i + 2]}, 0.0, material.roughness,
                    material.specular};
    // rcsplat's BRDF in double, with its weight from the quadrature kept above.
    ref::Material no_layer = m;
    no_layer.specular = 0.0;
    double weight = 1.0 - m.specular * ours_weight_albedo(material.roughness, wo.z);
    auto diffuse = ref::reference_brdf(no_layer, wo, wi, true, false), spec = ref::reference_brdf(m, wo, wi, false, true);
    auto gltf = ref::reference_brdf(m, wo, wi, true, true, ref::DiffuseWeight::per_microfacet);
    auto old = ref::reference_brdf(m, wo, wi, true, true, ref::DiffuseWeight::view_fresnel);
    for (size_t c = 0; c < 3; ++c) {
      double ours = weight * diffuse[c] + spec[c];
      double direct = img.direct[3 * i + c];
      if (!(ours > 0.0)) continue;
      rendered += direct;
      appendix_b += direct * gltf[c] / ours;
      view_fresnel += direct * old[c] / ours;
    }
    ++pixels;
  }
  std::printf("%s %dx%d, %zu rough dielectric pixels (device %s)\n", argv[1], settings.width, settings.height, pixels,
              gpu.device_info().name.c_str());
  std::printf("rcsplat / appendix B: %.4f\n1 - F(n.v) (before issue 41) / appendix B: %.4f\n", rendered / appendix_b,
              view_fresnel / appendix_b);
  return pixels > 0 ? 0 : 1;
}
