// --denoise: Intel Open Image Denoise (image/denoiser.h) on the light a frame samples per pixel, after the frame. The
// cache's indirect light is smooth (interpolated records) and stays as it is; what is noisy is what each pixel
// samples itself: direct light from emitters and the environment (shadow rays; a frame lit by punctual lights alone
// has none), and the glossy pass's sharp lobes. Each is denoised on its own with the G-buffer's albedo and normal as
// guides, and the frame is composed again: colour = emission + direct + (indirect - glossy) + glossy. Path tracing's
// colour and indirect light are denoised whole (the competitor users pick: path tracing + a denoiser).
#pragma once
#include "image/denoiser.h"
#include "render/frame.h"

namespace rcsplat {

// What denoise_frame filters: direct light when the frame samples it (emitters or an environment), and the glossy
// layer when the frame has one; path tracing's colour and indirect. Needs the frame's layers on the host
// (RenderSettings::color_only off).
struct DenoiseChoice {
  bool direct_sampled = false;  // area lights or an environment: the direct layer is noisy
};

// Denoises img in place: the denoised layers take the layers' names (RGB, direct, indirect, glossy), and the layers as
// rendered move to noisy, noisy_direct, noisy_indirect, noisy_glossy. Records what it did in img.stats.denoise. A
// frame with nothing sampled per pixel is left as it is (stats.denoise.layers empty).
void denoise_frame(const Denoiser& denoiser, const DenoiseChoice& choice, RenderedImage& img);

}  // namespace rcsplat
