#include "render/denoise_frame.h"

#include <chrono>
#include <cmath>

#include "util/error.h"

namespace rcsplat {

void denoise_frame(const Denoiser& denoiser, const DenoiseChoice& choice, RenderedImage& img) {
  const auto start = std::chrono::steady_clock::now();
  const size_t floats = size_t(img.width) * size_t(img.height) * 3;
  if (img.albedo.size() != floats || img.normal.size() != floats || img.color.size() != floats)
    throw Error("--denoise needs the frame's albedo and normal layers");
  const DenoiseGuides guides{&img.albedo, &img.normal};
  img.stats.denoise.device = denoiser.device_name();
  std::string& layers = img.stats.denoise.layers;
  auto add_name = [&](const char* name) {
    if (!layers.empty()) layers += ' ';
    layers += name;
  };
  if (img.stats.gi == GiMethod::path) {
    img.noisy_color = img.color;
    denoiser.denoise(img.color, img.width, img.height, guides);
    add_name("color");
    if (img.indirect.size() == floats) {
      const auto indirect_start = std::chrono::steady_clock::now();
      img.noisy_indirect = img.indirect;
      denoiser.denoise(img.indirect, img.width, img.height, guides);
      add_name("indirect");
      img.stats.denoise.indirect_only_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - indirect_start).count();
    }
  } else {
    const bool direct = choice.direct_sampled && img.direct.size() == floats;
    const bool glossy = img.glossy.size() == floats && img.indirect.size() == floats;
    if (!direct && !glossy) return;
    img.noisy_color = img.color;
    if (direct) {
      img.noisy_direct = img.direct;
      denoiser.denoise(img.direct, img.width, img.height, guides);
      add_name("direct");
    }
    if (glossy) {
      img.noisy_glossy = img.glossy;
      img.noisy_indirect = img.indirect;
      denoiser.denoise(img.glossy, img.width, img.height, guides);
      for (size_t i = 0; i < floats; ++i) img.indirect[i] += img.glossy[i] - img.noisy_glossy[i];
      add_name("glossy");
    }
    for (size_t i = 0; i < floats; ++i) {
      const float c = img.emission[i] + img.direct[i] + img.indirect[i];
      img.color[i] = std::isfinite(c) ? c : 0.0f;
    }
  }
  img.stats.denoise.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rcsplat
