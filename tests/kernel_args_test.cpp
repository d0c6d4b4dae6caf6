// Kernels are bound by name (host/cl/named_kernel.h): the host's names and types are checked against what the
// compiled kernels report (clGetKernelArgInfo, programs built with -cl-kernel-arg-info). Every kernel of every program
// a full set of renders builds must have been launched with all its parameters set, by name, in its own order (so
// that a driver without argument information, which binds by call order, binds them right too); and a binding that
// swaps two buffers must fail with the kernel's and the parameter's names.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "reference/world_record_grid.h"
#include "cl/device_scene.h"
#include "cl/embedded_kernels.h"
#include "passes/ray_cast_pass.h"
#include "passes/scan_pass.h"
#include "passes/splat_pass.h"
#include "passes/caustic_map_pass.h"
#include "passes/glossy_pass.h"
#include "passes/grid_sort_pass.h"
#include "passes/photon_map_pass.h"
#include "render/renderer.h"
#include "scene/cornell_box.h"
#include "pass_probe.h"
#include "test_support.h"
#include "util/error.h"

namespace rcsplat {
namespace {

// Every kernel the sources define (`__kernel void NAME` in each embedded .cl file): the list the test demands, so
// that a new kernel is covered without anyone adding it here.
std::set<std::string> every_kernel_in_the_sources() {
  std::set<std::string> names;
  const std::regex kernel_declaration(R"(__kernel\s+void\s+([A-Za-z_][A-Za-z_0-9]*))");
  for (const auto& [file, source] : embedded_kernel_sources()) {
    if (file.size() < 3 || file.substr(file.size() - 3) != ".cl") continue;
    for (auto it = std::sregex_iterator(source.begin(), source.end(), kernel_declaration); it != std::sregex_iterator();
         ++it)
      names.insert((*it)[1].str());
  }
  return names;
}

// The built-in Cornell box with a radiance-cached floor (metal, roughness 0.6: LOBE_HSH) and a glossy tall box
// (roughness 0.2: LOBE_GLOSSY), so that the radiance cache's, the glossy pass's and the caustic map's kernels run too.
Scene cornell_box_with_glossy_and_cached_lobes() {
  Scene scene = make_cornell_box();
  SceneMaterial floor = scene.materials[0], box = scene.materials[0];
  floor.metallic = 1.0f;
  floor.roughness = 0.6f;
  box.roughness = 0.2f;
  box.specular = 1.0f;  // a dielectric: without a specular layer or metal the box would be Lambertian
  scene.materials.push_back(floor);
  scene.materials.push_back(box);
  scene.triangle_material[0] = scene.triangle_material[1] = uint32_t(scene.materials.size() - 2);
  for (size_t t = 22; t < 32; ++t) scene.triangle_material[t] = uint32_t(scene.materials.size() - 1);
  return scene;
}

TEST(KernelArgs, EveryKernelIsBoundByNameInItsOwnOrder) {
  const std::unique_ptr<GpuContext> own = test::fresh_gpu();  // every kernel built here is this test's
  GpuContext& gpu = *own;
  Scene scene = cornell_box_with_glossy_and_cached_lobes();
  RenderSettings settings = test::one_bounce_one_sample();
  settings.width = settings.height = 32;
  settings.light_samples = 4;
  settings.cache.theta_strata = 4;
  settings.cache.phi_strata = 8;
  settings.path.samples = 2;
  for (GiMethod gi : {GiMethod::splat, GiMethod::octree, GiMethod::path, GiMethod::none}) {
    settings.gi = gi;
    render(gpu, scene, settings);
  }
  {
    RenderSettings direct_only = settings;  // a colour-only frame of direct light: its colour summed on the device
    direct_only.color_only = true;
    render(gpu, scene, direct_only);
  }
  {  // Glass: the G-buffer's weights for pixels that look through it (kernels/gbuffer.cl weigh_through_glass). The
    // tall box as a volume whose light comes by the glass caustic map, which every kernel's SCENE_ARGS then carry
    // (kernels/glass_caustics.cl adds it at the pixels).
    Scene glass = scene;
    glass.materials.back().transmission = 1.0f;
    glass.materials.back().thickness = 1.0f;
    glass.glass_light.caustics = true;
    glass.glass_light.photons = 4096;
    RenderSettings through = settings;
    through.gi = GiMethod::splat;
    render(gpu, glass, through);
  }
  // Records kept across frames: a second frame fits the first one's to its view (kernels/placement.cl).
  {
    RenderSettings kept = settings;
    kept.gi = GiMethod::splat;
    kept.keep_records = true;
    Renderer renderer(gpu, scene);
    renderer.render(kept);
    renderer.render(kept);
  }
  // The photon map (two bounces) and the sub-pixels' fill (four pixel samples) run only when asked for.
  settings.gi = GiMethod::splat;
  settings.bounces = 2;
  settings.bounce_method = BounceMethod::photons;
  settings.photon_paths = 1024;
  settings.pixel_samples = 4;
  render(gpu, scene, settings);
  // A frame that asks for its colour alone sums the summary's counts on the device (passes/layer_pass.h); with one
  // bounce the glossy pass reads no record, so the records stay there too and their clamps are counted there.
  settings.color_only = true;
  render(gpu, scene, settings);
  RenderSettings one_bounce = settings;
  one_bounce.bounces = 1;
  render(gpu, scene, one_bounce);
  settings.color_only = false;
  // The record trace's other shapes than the device's (GroupSizes::record_trace: fused on a CPU device, the wavefront
  // on a GPU), with the photon map too.
  const GroupSizes device_choice = gpu.groups();
  for (RecordTrace trace : {RecordTrace::fused, RecordTrace::split, RecordTrace::wavefront}) {
    if (trace == device_choice.record_trace) continue;
    GroupSizes shape = device_choice;
    shape.record_trace = trace;
    test::PassProbe::set_groups(gpu, shape);
    render(gpu, scene, settings);
    test::PassProbe::set_groups(gpu, device_choice);
  }
  PhotonHit photon{};
  photon.hit = 1;
  photon.normal[1] = 1.0f;
  photon.flux[0] = photon.incident[0] = 1.0f;
  PhotonHit beside = photon;  // a photon's own estimate leaves it out: a second one lights it
  beside.position[0] = 0.01f;
  PhotonMapPass map(gpu, build_photon_map({photon, beside}, 1.0, 1, 1));
  EXPECT_GT(test::photon_radiance_at(gpu, map, {{{0.0f, 0.0f, 0.0f, 0.0f}}}, {{{0.0f, 1.0f, 0.0f, 0.0f}}})[0].s[0], 0.0f);
  CausticMapPass caustics(gpu, {photon, beside}, 0.1f);
  EXPECT_GT(test::caustic_irradiance_at(gpu, caustics, {{{0.0f, 0.0f, 0.0f, 0.0f}}}, {{{0.0f, 1.0f, 0.0f, 0.0f}}})[0].s[0], 0.0f);
  Bvh8 bvh = build_bvh8(scene.positions);
  DeviceScene device(gpu, scene, bvh);
  CacheRecord record{};
  record.normal[1] = 1.0f;
  record.radius = 1.0f;
  record.irradiance[0] = 1.0f;
  for (float& h : record.horizon) h = 1e30f;
  const std::vector<CacheRecord> one_record{record};
  const WorldRecordGrid record_grid = build_world_record_grid(one_record, 0.5f);
  GlossyPass glossy(gpu, device, false);
  EXPECT_GT(test::PassProbe::cached_irradiance_at(glossy, one_record, record_grid, {{{0.0f, 0.0f, 0.0f, 0.0f}}},
                                        {{{0.0f, 1.0f, 0.0f, 0.0f}}})[0].s[0],
            0.0f);
  RayCastPass caster(gpu, device);
  glm::vec3 centre = 0.5f * (scene.bounds_min() + scene.bounds_max());  // inside the closed box: every ray hits
  RayDesc ray{{centre.x, centre.y, centre.z}, 0.0f, {0.0f, -1.0f, 0.0f}, 1e30f};
  caster.set_rays({ray});
  caster.cast_closest();
  caster.cast_occlusion();
  EXPECT_GE(caster.closest_hits()[0].prim, 0);
  // A scan of more than one block adds the blocks' offsets (the frames above scan at most one block).
  ScanPass scan(gpu);
  const cl::Buffer scanned = gpu.buffer(CL_MEM_READ_WRITE, 2000 * sizeof(cl_uint), "test");
  scan.exclusive(gpu.upload(std::vector<cl_uint>(2000, 1u)), 2000, scanned);
  EXPECT_EQ(gpu.download<cl_uint>(scanned, 2000)[1999], 1999u);

  // The photon map's grid sort (frames above may keep too few photons to sort any).
  GridSortPass grid_sort(gpu);
  const PhotonMapParams grid = photon_grid_params(std::vector<PhotonHit>{photon, beside}, 1.0f);
  const cl::Buffer sorted = gpu.buffer(CL_MEM_READ_WRITE, 2 * sizeof(PhotonHit), "test");
  const cl::Buffer starts = gpu.buffer(CL_MEM_READ_WRITE, (grid.bucket_count + 1) * sizeof(cl_uint), "test");
  grid_sort.sort(gpu.upload(std::vector<PhotonHit>{photon, beside}), sizeof(PhotonHit) / 4, 2, grid, sorted, starts);
  EXPECT_EQ(gpu.download<cl_uint>(starts, grid.bucket_count + 1).back(), 2u);

  std::set<std::string> built = test::PassProbe::built_kernel_names(gpu);
  const std::set<std::string> every_kernel = every_kernel_in_the_sources();
  EXPECT_GE(every_kernel.size(), 36u) << "the sources' kernels were not all found";
  for (const std::string& expected : every_kernel) EXPECT_TRUE(built.count(expected)) << expected << " was not built";
  for (const std::string& name : built) {
    auto launched = test::PassProbe::launched_kernels(gpu).find(name);
    ASSERT_NE(launched, test::PassProbe::launched_kernels(gpu).end()) << "kernel " << name << " was never launched";
    EXPECT_TRUE(launched->second) << "kernel " << name << ": parameters not all set in the kernel's order";
  }
  NamedKernel sample = gpu.kernel("splat.cl", "splat_records");
  EXPECT_TRUE(sample.bound_by_name()) << "the test device reports no argument names";
}

TEST(KernelArgs, ASwapOrAMissingArgumentIsAnErrorNamingTheKernel) {
  GpuContext& gpu = test::gpu();
  cl::Buffer sums(gpu.context(), CL_MEM_READ_WRITE, 64), counts(gpu.context(), CL_MEM_READ_WRITE, 64);
  NamedKernel splat = gpu.kernel("splat.cl", "splat_records");
  try {
    splat.set_buffer<cl_uint>("sums", counts);  // the planted swap: the counts buffer bound as the sums
    ADD_FAILURE() << "a uint buffer bound as 'sums' (long*)";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("splat_records"), std::string::npos) << message;
    EXPECT_NE(message.find("'sums'"), std::string::npos) << message;
  }
  EXPECT_THROW(splat.set("accuracy", 0.5f), Error);  // no such parameter: it travels in SplatParams
  EXPECT_THROW(splat.set("params", cl_uint(1)), Error);
  splat.set_buffer<cl_long>("sums", sums).set_buffer<cl_uint>("counts", counts);
  try {
    splat.launch(1, 1);
    ADD_FAILURE() << "launched with parameters unset";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("was not set"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rcsplat
