// The irradiance cache's controls (docs/ALGORITHM.md sections 3 to 7): defined, defaulted and validated here, and turned
// into the record kernel's parameters here. Both cache methods (splat and octree) read them.
#pragma once
#include <cstdint>

#include "kernels/cache_math.h"
#include "kernels/shared_types.h"

namespace rcsplat {

// The most guided rays a record may take beside its strata (--guide-rays).
constexpr unsigned kMaxGuideRays = 4096;

struct CacheSettings {
  float accuracy = 0.3f;       // a: smaller means more records and less error (MIN_ACCURACY .. MAX_ACCURACY)
  unsigned theta_strata = 16;  // hemisphere rays per record: M x N
  unsigned phi_strata = 32;
  // Rays for the records placed at the finest level (spacing 1), which reach only a few pixels each; 0: M x N too.
  unsigned fine_theta_strata = 0, fine_phi_strata = 0;
  // A record's reach a * R is clamped to [min, max] pixel footprints at the record (as pbrt-v2 clamps its
  // contribution extent), so R itself to [min, max] / a. Keeps records from crowding corners and from vanishing on
  // open areas. The command line's --spacing MIN,MAX.
  float min_reach_pixels = 3.0f;
  float max_reach_pixels = 20.0f;
  // The radius rule: 0 for Ward's split sphere (the harmonic mean hit distance), or the error budget C of the
  // occlusion Hessian (Schwarzhaupt et al. 2012; kernels/record_hessian.h), per output pixel: anti-aliasing's sub-pixel
  // frame scales it (host/render/pixel_samples.cpp). The command line's --hessian-error. Not the default: C = 750
  // gave Sponza 1024 x 768 the same error in 0.91x the frame and the Cornell box 7% / 14% less relMSE / block error,
  // but Sibenik 2-5x the block error (noise read as curvature shrinks radii where its few bright patches make records
  // noisy; benchmarks/RESULTS.md "Record radii").
  float hessian_error = 0.0f;
  // Adaptive rays: above 0, each record is first traced with half the strata each way (M/2 x N/2), and those whose
  // relative error (kernels/records.cl) is above this are traced again with all M x N. The command line's
  // --adaptive-rays.
  float adaptive_error = 0.0f;
  int coarsest_spacing_pixels = 32;
  // Placement stops at this spacing (with its extra rounds). Anti-aliasing sets it to one output pixel in sub-pixels, so
  // records are placed as at one sample; the sub-pixels they leave unreached take the best-weighted record near them
  // (the splat's fill_uncovered).
  int finest_spacing_pixels = 1;
  // The light guide (kernels/light_guide.h): rays per record aimed at the brightest directly lit places, beside the
  // M x N strata (0: no guide), and the photons that find those places. The command line's --guide-rays.
  unsigned guide_rays = 64;
  unsigned guide_photons = 1u << 16;  // record placement starts on this pixel grid and halves it down to 1
  // Records follow the scene, not the image: the spacings and reaches above, in pixels, hold for an image this many
  // output lines high, and a taller one scales them by its height over this (scale_placement_to_image). 0: they hold
  // at every size. The command line's --placement-lines.
  int placement_lines = 0;
  bool operator==(const CacheSettings&) const = default;
};

// The spacings and reaches of `cache` for an image `height` output lines high (CacheSettings::placement_lines).
void scale_placement_to_image(CacheSettings& cache, int height);

constexpr float kMinAccuracy = MIN_ACCURACY;
constexpr float kMaxAccuracy = MAX_ACCURACY;

// Throws rcsplat::Error naming the option (--accuracy, --hemisphere, --fine-hemisphere, --spacing) that is out of
// range: the command line refuses such values when it parses them, and render() before it starts.
void validate_cache_settings(const CacheSettings& cache);

// The record kernel's sampling parameters for records placed at this grid spacing: the fine hemisphere at the finest
// spacing when one is set, and the reach clamps turned into radius clamps.
HemisphereParams hemisphere_params(const CacheSettings& cache, unsigned seed, int spacing);
// The radius clamp's minimum in pixel footprints (the minimum reach over a).
float min_radius_pixels(const CacheSettings& cache);
float max_radius_pixels(const CacheSettings& cache);
// The largest M any level uses (the record kernel is compiled for it).
unsigned largest_theta_strata(const CacheSettings& cache);
// Placement starts at the largest power of two not above the coarsest spacing.
int coarsest_placement_spacing(const CacheSettings& cache);

}  // namespace rcsplat
