// An image judged against a reference, as `compare` prints it and `sweep` tabulates it: per layer (the full image and,
// where both files carry it, the indirect layer) relMSE, RMSE, MAE, relMSE of block means, and mean LDR-FLIP of the
// tone-mapped images; less the expected contribution of a path-traced reference's own noise where it carries its
// variance. Both views of error matter: per-pixel relMSE flatters a cache (its error is blotches, not noise), block
// relMSE sees blotches, FLIP sees what a viewer sees.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "image/error_metrics.h"

namespace rcsplat {

struct LayerComparison {
  std::string layer;  // "full" or "indirect"
  ErrorMetrics pixel;
  std::optional<double> block_rel_mse;  // absent when the image is smaller than one block
  double mean_flip = 0.0;
  double mean_ratio = 0.0;  // the image's mean over the reference's (all channels): too dark or too bright overall
  std::optional<double> reference_noise, block_reference_noise;  // expected relMSEs from the reference's variance
  std::vector<float> flip_map, rel_mse_map;  // per pixel, for heat maps
  // The relMSEs less the reference's own noise, where the reference carries its variance.
  std::optional<double> rel_mse_less_reference_noise() const {
    return reference_noise ? std::optional<double>(pixel.rel_mse - *reference_noise) : std::nullopt;
  }
  std::optional<double> block_rel_mse_less_reference_noise() const {
    return block_reference_noise ? std::optional<double>(*block_rel_mse - *block_reference_noise) : std::nullopt;
  }
};

struct ImageComparison {
  std::string image_path, reference_path;
  int width = 0, height = 0, block = 8;
  float exposure_stops = 0.0f;  // the tone mapping FLIP judges, as in the PNGs
  std::vector<LayerComparison> layers;
  nlohmann::json rendered_differently = nlohmann::json::array();  // attributes that make the two renders differ
  bool finer_pixel_reference = false;                             // the reference integrates pixels more finely
  const LayerComparison* find(const std::string& layer) const;
};

// Reads both EXRs; throws rcsplat::Error naming a file on bad input or different sizes.
ImageComparison compare_exr_files(const std::string& image_path, const std::string& reference_path, int block,
                                  float exposure_stops);
nlohmann::json comparison_json(const ImageComparison& comparison);

}  // namespace rcsplat
