// Where the glossy pass spends its samples after its first round (kernels/glossy.cl): each output pixel's sub-pixels
// that sample a lobe took one chunk; the pixels whose estimated error gains most per chunk take more, doubling their
// chunks (2^level each) in later rounds, until the frame's budget is spent.
#pragma once
#include <cstdint>
#include <vector>

#include <CL/cl_platform.h>

namespace rcsplat {

// The most doublings a pixel takes: 2^5 = 32 chunks, 64 lobe samples a sub-pixel.
constexpr unsigned kGlossyMaxLevel = 5;

// errors: per output pixel (width x height, row-major) what kernels/glossy.cl glossy_pixel_error wrote: the variance
// of its glossy light's luminance after one chunk a sub-pixel, the luminance of its other light, its refined
// sub-pixels (a), the luminance of its glossy light. A pixel's count is decided from its 8 neighbours' samples, never
// its own: its own samples then stay an unbiased estimate whatever count it ends with. (Decided from its own, a pixel
// whose first samples missed a small bright reflection looked quiet and kept its zero, one that found it took more
// and diluted it: the frame's glossy light came out at a third of its mean on the corridor of
// GlossyKernel.RoundsByEstimatedErrorKeepTheLightsMean.) Its relative error e is the neighbours' mean variance over
// (L^2 + 0.01), compare's relMSE (host/image/error_metrics.h), L its other light plus the neighbours' mean glossy light.
// Doubling a pixel from 2^L chunks costs a 2^L chunks and takes e / 2^(L+1) off its error (the variance falls as
// 1 / chunks): the doublings are taken in order of gain per chunk, e / (2 a 4^L), down to the threshold that spends
// at most extra_chunks. Returns each pixel's level (0: the first round's chunk only); the same input gives the same
// levels.
std::vector<uint8_t> glossy_refinement_levels(const std::vector<cl_float4>& errors, int width, int height,
                                              double extra_chunks, unsigned max_level = kGlossyMaxLevel);

}  // namespace rcsplat
