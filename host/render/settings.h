// What a render is asked to do: resolution, camera, light samples, and how indirect light is computed.
#pragma once
#include <set>
#include <string>

#include "cache/cache_settings.h"
#include "render/camera.h"

namespace rcsplat {

enum class GiMethod { none, splat, octree, path };
// How the cache's records find the bounces after the first (--bounces 2 and more): path: each record ray's path goes
// on from its hit (kernels/bounce.h); photons: the hit reads a photon map (kernels/photon_map.h). The path tracer
// always continues its paths.
// auto: photons for the cache methods unless the scene has an environment (render/bounce_choice.h).
enum class BounceMethod { automatic, path, photons };
const char* bounce_method_name(BounceMethod method);

constexpr unsigned kMaxBounces = 16;
// --photons 0: photons are shot in rounds of this many until the map holds as many (at most kPhotonRounds rounds: an
// open scene loses most of its photons to the sky).
constexpr unsigned kPhotonMapPhotons = 1u << 19, kPhotonRounds = 8;
const char* gi_method_name(GiMethod method);

struct PathSettings {
  unsigned samples = 64;  // per pixel
  bool stratified = false;
  // Over the pixel's area: --pixel-samples N = s^2 becomes N rounds of the frame, round r's camera rays through a
  // random point of cell r of an s x s grid over each pixel (stratified jitter, so the pixel's value converges to its
  // area integral, edges to their covered fraction). false: one s-times larger frame through the rotated grid's
  // points (render/pixel_samples.h), the very points a cache render shades (tests that isolate the cache's error
  // compare there).
  bool pixel_area = true;
};

struct RenderSettings {
  int width = 0, height = 0;  // 0: derived (see resolve_resolution)
  int camera = 0;
  CameraOverrides camera_overrides;
  unsigned light_samples = 16;  // per pixel on emissive triangles; rounded up to a square number of strata
  // Cache methods: light_samples is the frame's average per output pixel, spent first on one sample a sub-pixel and then
  // where the estimated error gains most (passes/direct_pass.h); false, or path tracing: every pixel's count.
  bool light_adaptive = true;
  // Cache methods: samples of a glossy pixel's specular lobe (kernels/glossy.cl), per output pixel as light_samples
  // and split among its sub-pixels: with glossy_adaptive, the frame's average (its budget), spent first on a chunk of
  // every sub-pixel and then where the estimated error gains most (passes/glossy_pass.h); without it, every glossy
  // pixel's count.
  unsigned glossy_samples = 16;
  bool glossy_adaptive = true;
  // Radiance caching of LOBE_HSH pixels: the HSH order (n^2 coefficients a channel), 0 = chosen from the cached
  // materials' roughness (the smallest order holding 95% of what order 10 holds of every cached lobe).
  unsigned hsh_order = 0;
  unsigned seed = 0;
  // Indirect bounces every method gathers (kernels/bounce.h): 1 is the first bounce lit directly; each more continues
  // the path from the bounce's hit. 0 (the command line's default too): chosen from the scene
  // (render/bounce_choice.h).
  unsigned bounces = 0;  // 0 .. kMaxBounces
  BounceMethod bounce_method = BounceMethod::automatic;
  // --bounce-method photons: photons shot from the lights, each landing up to `bounces` times (0: in rounds of
  // kPhotonMapPhotons / (bounces - 1), until the map holds about kPhotonMapPhotons), and how many of them the density estimate's radius holds on average over the scene's
  // surface.
  unsigned photon_paths = 0;
  unsigned photon_neighbours = 64;
  // --bounce-method photons: record rays that land closer than this many gather radii continue their path one bounce
  // and read there the map without its last landing, instead of reading it where they land, whose disc would blur
  // the record's own contacts and recesses (Jensen's final gather; benchmarks/RESULTS.md "Short record rays continue
  // a bounce").
  float short_ray_paths = 2.0f;
  // --bounce-method photons: a record ray whose hit's photon estimate summed fewer photons than this (the map's disc
  // holds photon_neighbours on average), or that finds no lookup photon near, continues its path instead of reading
  // the map: where few photons land, as in a room lit through a gap, a lookup that finds none would read black
  // (docs/NOTES.md "Issue 41: photons where they are scarce"). 0: every ray reads the map, black where it finds none.
  float photon_min_support = 4.0f;
  // Cache methods, scenes with a sharp lobe (LOBE_GLOSSY): photons shot for the caustic map, which carries light ->
  // glossy -> rough paths to the pixels instead of the records' rays (kernels/caustic_map.cl); its radius holds
  // photon_neighbours of them on average. 0: no caustic map, the records count those paths through their rays (one
  // stratum on a highlight can then make a record a bright disc). 2^20: on textured Sibenik 0.99x the block error
  // of 2^19 for 0.12 s more (benchmarks/RESULTS.md "Issue 41, items 1 and 2").
  unsigned caustic_photons = 1u << 20;
  // Cache methods, --bounces 2 or more: a glossy pixel's sample whose ray lands on a Lambertian or rough surface that a
  // record reaches takes the bounces after that hit from the records (found by position: kernels/world_records.h)
  // instead of continuing its path (kernels/glossy.cl). false (--glossy-paths): every sample continues its path.
  bool glossy_reads_records = true;
  GiMethod gi = GiMethod::splat;
  // The splat: irradiance records kept by the Renderer from frame to frame (render/kept_records.h; `animate` without
  // --cache-per-frame): each frame splats the kept records its view takes and places new ones only where none
  // reaches. At most kept_records_capacity are kept; the least recently used go first.
  bool keep_records = false;
  size_t kept_records_capacity = size_t(1) << 20;
  // Primary samples per pixel (render/pixel_samples.h): a square number; each pixel is an s x s grid of sub-pixels
  // rendered as pixels of an s-times larger frame and averaged. Light samples, path samples and record spacing are
  // per output pixel. 0 (the command line's default too): chosen by the plan (4 unless --spp does not divide by 4:
  // render/pixel_samples.h).
  unsigned pixel_samples = 0;
  // What pixel_samples 0 becomes, where --spp and the frame allow it: 4 for renders, 16 for references (a finer grid
  // than a render's: compare then counts the render's edge aliasing as its error).
  unsigned preferred_pixel_samples = 4;
  // Set by the plan for the s-times larger frame it renders (render/pixel_samples.h): s, whose sub-pixels then take
  // their points on a rotated grid (CameraParams::sub_pixel_side); 1 for a frame of its own.
  unsigned sub_pixel_side = 1;
  // Tests: scene switches (HAS_SPECULAR_BRDF, HAS_TEXTURES, ...) compiled on even where the scene does not need them.
  std::set<std::string> forced_switches;
  // The caller needs only the frame's colour (PNG outputs, walkthrough frames): no other layer comes back from the
  // device and the summary's counts are summed there (passes/layer_pass.h); a cache method's records stay there too,
  // but for those a walkthrough keeps and those the glossy pass's grid is built from (indirect_splat.cpp).
  bool color_only = false;
  // Pixels a piece of the image layers comes down in (passes/layer_pass.h); 0: LayerPass's own. Tests make it small.
  size_t layer_piece_pixels = 0;
  CacheSettings cache;
  PathSettings path;
};

// A frame whose layers other than the colour stay on the device (RenderSettings::color_only). Path tracing still
// brings back its sub-pixels' indirect light (indirect_path.cpp combines its two halves in double on the host).
inline bool layers_stay_on_device(const RenderSettings& s) { return s.color_only; }

}  // namespace rcsplat
