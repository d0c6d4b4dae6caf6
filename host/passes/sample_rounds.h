// Where a pass that samples in rounds spends its samples after the first (the glossy pass, kernels/glossy.cl; the
// direct light's area lights and environment peak, kernels/direct.cl): each output pixel's sampled sub-pixels took one
// chunk; the pixels whose estimated error gains most per chunk take more, doubling their chunks (2^level each) in
// later rounds, until the frame's budget is spent.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include <CL/cl_platform.h>

namespace rcsplat {

// The most doublings a pixel takes: 2^5 = 32 chunks a sub-pixel.
constexpr unsigned kRoundsMaxLevel = 5;

// errors: per output pixel (width x height, row-major) what the pass's error kernel wrote (kernels/glossy.cl
// glossy_pixel_error, kernels/direct.cl direct_pixel_error): the variance
// of its sampled light's luminance after one chunk a sub-pixel, the luminance of its other light, its refined
// sub-pixels (a), the luminance of its sampled light. A pixel's count is decided from its 8 neighbours' samples, never
// its own: its own samples then stay an unbiased estimate whatever count it ends with. (Decided from its own, a pixel
// whose first samples missed a small bright reflection looked quiet and kept its zero, one that found it took more
// and diluted it: the frame's glossy light came out at a third of its mean on the corridor of
// GlossyKernel.RoundsByEstimatedErrorKeepTheLightsMean.) Its relative error e is the neighbours' mean variance over
// (L^2 + 0.01), compare's relMSE (host/image/error_metrics.h), L its other light plus the neighbours' mean sampled
// light.
// Doubling a pixel from 2^L chunks costs a 2^L chunks and takes e / 2^(L+1) off its error (the variance falls as
// 1 / chunks): the doublings are taken in order of gain per chunk, e / (2 a 4^L), down to the threshold that spends
// at most extra_chunks. Returns each pixel's level (0: the first round's chunk only); the same input gives the same
// levels.
std::vector<uint8_t> refinement_levels(const std::vector<cl_float4>& errors, int width, int height,
                                              double extra_chunks, unsigned max_level = kRoundsMaxLevel);

// After a first round of one chunk a sampled sub-pixel: each output pixel's level for a budget of
// chunks_per_sampled_sub_pixel on average (the first round's one included), from the error kernel's estimates, with
// what the plan spends.
struct RoundsPlan {
  std::vector<uint8_t> levels;
  uint64_t sampled_sub_pixels = 0;  // the sub-pixels the estimates pooled (errors' s[2], summed)
  uint64_t chunks = 0;              // the first round's and the later rounds' together
  uint64_t refined_pixels = 0;      // output pixels of level 1 or more
};
RoundsPlan plan_rounds(const std::vector<cl_float4>& errors, int width, int height,
                       double chunks_per_sampled_sub_pixel);

// The chunks the levels add beyond the first round's (a pixel of level L: a (2^L - 1), a its errors' s[2]).
uint64_t chunks_added(const std::vector<uint8_t>& levels, const std::vector<cl_float4>& errors);

// Rounds 2.. for these levels: round r (1 .. kRoundsMaxLevel) lists, in order, the output pixels whose level is r or
// more, and run_round(list, first_chunk, chunks) adds chunks [2^(r-1), 2^r) to each of their sampled sub-pixels.
// Returns the rounds run, the first included.
unsigned run_later_rounds(
    const std::vector<uint8_t>& levels,
    const std::function<void(const std::vector<cl_uint>& listed, unsigned first_chunk, unsigned chunks)>& run_round);

}  // namespace rcsplat
