#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "image/error_metrics.h"
#include "image/image_io.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {

int run_compare(const CompareOptions& o) {
  int w = 0, h = 0, rw = 0, rh = 0;
  std::vector<float> image = read_exr_rgb(o.image_path, w, h);
  std::vector<float> reference = read_exr_rgb(o.reference_path, rw, rh);
  if (w != rw || h != rh)
    throw Error(o.image_path + " is " + std::to_string(w) + "x" + std::to_string(h) + " but " + o.reference_path +
                " is " + std::to_string(rw) + "x" + std::to_string(rh));
  // Renders of other light, bounces or pixel sampling differ in what they show, not by error: say so, loudly.
  const ExrAttributes image_attributes = read_exr_attributes(o.image_path);
  const ExrAttributes reference_attributes = read_exr_attributes(o.reference_path);
  nlohmann::json rendered_differently = nlohmann::json::array();
  bool area_reference = false;
  for (const char* key : {"rcsplat:scene", "rcsplat:bounces", "rcsplat:environment", "rcsplat:pixel_samples"}) {
    auto in_image = image_attributes.find(key), in_reference = reference_attributes.find(key);
    if (in_image == image_attributes.end() || in_reference == reference_attributes.end() ||
        in_image->second == in_reference->second)
      continue;
    // A reference on a finer sub-pixel grid integrates each pixel's area more closely: what it shows is what the
    // image should, so the difference is the image's error, its edges' aliasing included.
    if (std::string(key) == "rcsplat:pixel_samples" && std::atof(in_reference->second.c_str()) >
                                                             std::atof(in_image->second.c_str())) {
      area_reference = true;
      log_info("the reference integrates each pixel over " + in_reference->second + " sub-pixels, the image over " +
               in_image->second + ": the error includes the image's edge aliasing");
      continue;
    }
    log_warning(std::string("the images differ in ") + key + ": " + in_image->second + " against " +
                in_reference->second + "; the numbers below measure that difference, not an error");
    rendered_differently.push_back(
        {{"attribute", key}, {"image", in_image->second}, {"reference", in_reference->second}});
  }
  ErrorMetrics full = image_error(image, reference);
  const bool blocks = w >= o.block && h >= o.block;
  const double full_block = blocks ? block_rel_mse(image, reference, w, h, o.block) : 0.0;
  const std::string block_name = std::to_string(o.block) + "x" + std::to_string(o.block) + " relMSE";
  std::printf("%-10s %-12s %-12s %-12s %s\n", "layer", "relMSE", "RMSE", "MAE", blocks ? block_name.c_str() : "");
  std::printf("%-10s %-12.4e %-12.4e %-12.4e %.4e\n", "full", full.rel_mse, full.rmse, full.mae, full_block);
  nlohmann::json j = {{"image", o.image_path}, {"reference", o.reference_path}, {"block", o.block},
                      {"full", {{"rel_mse", full.rel_mse}, {"rmse", full.rmse}, {"mae", full.mae},
                                {"block_rel_mse", full_block}}},
                      {"rendered_differently", rendered_differently}, {"finer_pixel_reference", area_reference}};
  // The indirect layer alone: noisy direct light sets a floor on the full image's error that says nothing of the cache.
  if (exr_has_layer(o.image_path, "indirect") && exr_has_layer(o.reference_path, "indirect")) {
    std::vector<float> ref = read_exr_layer(o.reference_path, "indirect", rw, rh);
    std::vector<float> indirect = read_exr_layer(o.image_path, "indirect", w, h);
    ErrorMetrics ind = image_error(indirect, ref);
    const double ind_block = blocks ? block_rel_mse(indirect, ref, w, h, o.block) : 0.0;
    std::printf("%-10s %-12.4e %-12.4e %-12.4e %.4e\n", "indirect", ind.rel_mse, ind.rmse, ind.mae, ind_block);
    j["indirect"] = {{"rel_mse", ind.rel_mse}, {"rmse", ind.rmse}, {"mae", ind.mae}, {"block_rel_mse", ind_block}};
    // A path-traced reference carries its own noise, which adds its expected relMSE to every comparison against it.
    if (exr_has_layer(o.reference_path, "indirect_variance")) {
      std::vector<float> var = read_exr_layer(o.reference_path, "indirect_variance", rw, rh);
      double noise = 0.0;
      for (size_t i = 0; i < ref.size(); ++i) noise += var[i] / (double(ref[i]) * ref[i] + kRelMseOffset) / double(ref.size());
      std::printf("reference noise: expected indirect relMSE %.4e (from its variance); relMSE less that: %.4e\n", noise,
                  ind.rel_mse - noise);
      j["indirect"]["reference_noise"] = noise;
      j["indirect"]["rel_mse_less_reference_noise"] = ind.rel_mse - noise;
      if (blocks) {
        const double block_noise = block_rel_mse_of_noise(var, ref, w, h, o.block);
        std::printf("reference noise: expected indirect %s %.4e; %s less that: %.4e\n", block_name.c_str(), block_noise,
                    block_name.c_str(), ind_block - block_noise);
        j["indirect"]["block_reference_noise"] = block_noise;
        j["indirect"]["block_rel_mse_less_reference_noise"] = ind_block - block_noise;
      }
    }
  } else {
    std::printf("indirect   (no indirect layer in both images)\n");
  }
  if (!o.heatmap_path.empty()) {
    write_png_display(o.heatmap_path, w, h, error_heatmap(pixel_rel_mse(image, reference)));
    std::printf("wrote      %s (per-pixel relMSE, log scale: dark blue 1e-6 ... white 1)\n", o.heatmap_path.c_str());
  }
  if (!o.json_path.empty()) write_text_file(o.json_path, j.dump(2) + "\n");
  return 0;
}

}  // namespace rcsplat
