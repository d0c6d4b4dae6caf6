#include "image/comparison.h"

#include <cstdlib>
#include <filesystem>

#include "image/flip.h"
#include "image/image_io.h"
#include "image/tone_map.h"
#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {

LayerComparison compare_layer(const std::string& name, const std::vector<float>& image,
                              const std::vector<float>& reference, int width, int height, int block,
                              float exposure_stops) {
  LayerComparison c;
  c.layer = name;
  c.pixel = image_error(image, reference);
  double image_sum = 0.0, reference_sum = 0.0;
  for (size_t i = 0; i < image.size() && i < reference.size(); ++i) image_sum += image[i], reference_sum += reference[i];
  c.mean_ratio = reference_sum > 0.0 ? image_sum / reference_sum : 0.0;
  if (width >= block && height >= block) c.block_rel_mse = block_rel_mse(image, reference, width, height, block);
  FlipResult flip =
      ldr_flip(display_image(reference, exposure_stops), display_image(image, exposure_stops), width, height);
  c.mean_flip = flip.mean;
  c.flip_map = std::move(flip.error);
  std::vector<double> rel = pixel_rel_mse(image, reference);
  c.rel_mse_map.assign(rel.begin(), rel.end());
  return c;
}

// Renders of other light, bounces or pixel sampling differ in what they show, not by error: say so, loudly.
void check_attributes(ImageComparison& c) {
  const ExrAttributes image_attributes = read_exr_attributes(c.image_path);
  const ExrAttributes reference_attributes = read_exr_attributes(c.reference_path);
  for (const char* key : {"rcsplat:scene", "rcsplat:bounces", "rcsplat:environment", "rcsplat:pixel_samples"}) {
    auto in_image = image_attributes.find(key), in_reference = reference_attributes.find(key);
    if (in_image == image_attributes.end() || in_reference == reference_attributes.end() ||
        in_image->second == in_reference->second)
      continue;
    std::error_code ec;  // one scene file named by two paths (relative and absolute) is the same scene
    if (std::string(key) == "rcsplat:scene" && std::filesystem::equivalent(in_image->second, in_reference->second, ec))
      continue;
    // A reference on a finer sub-pixel grid integrates each pixel's area more closely: what it shows is what the
    // image should, so the difference is the image's error, its edges' aliasing included.
    if (std::string(key) == "rcsplat:pixel_samples" &&
        std::atof(in_reference->second.c_str()) > std::atof(in_image->second.c_str())) {
      c.finer_pixel_reference = true;
      log_info("the reference integrates each pixel over " + in_reference->second + " sub-pixels, the image over " +
               in_image->second + ": the error includes the image's edge aliasing");
      continue;
    }
    log_warning(std::string("the images differ in ") + key + ": " + in_image->second + " against " +
                in_reference->second + "; the numbers below measure that difference, not an error");
    c.rendered_differently.push_back(
        {{"attribute", key}, {"image", in_image->second}, {"reference", in_reference->second}});
  }
}

}  // namespace

const LayerComparison* ImageComparison::find(const std::string& layer) const {
  for (const LayerComparison& l : layers)
    if (l.layer == layer) return &l;
  return nullptr;
}

ImageComparison compare_exr_files(const std::string& image_path, const std::string& reference_path, int block,
                                  float exposure_stops) {
  ImageComparison c;
  c.image_path = image_path;
  c.reference_path = reference_path;
  c.block = block;
  c.exposure_stops = exposure_stops;
  int rw = 0, rh = 0;
  std::vector<float> image = read_exr_rgb(image_path, c.width, c.height);
  std::vector<float> reference = read_exr_rgb(reference_path, rw, rh);
  if (c.width != rw || c.height != rh)
    throw Error(image_path + " is " + std::to_string(c.width) + "x" + std::to_string(c.height) + " but " +
                reference_path + " is " + std::to_string(rw) + "x" + std::to_string(rh));
  check_attributes(c);
  c.layers.push_back(compare_layer("full", image, reference, c.width, c.height, block, exposure_stops));
  // The indirect layer alone: noisy direct light sets a floor on the full image's error that says nothing of the cache.
  if (exr_has_layer(image_path, "indirect") && exr_has_layer(reference_path, "indirect")) {
    std::vector<float> ref = read_exr_layer(reference_path, "indirect", rw, rh);
    std::vector<float> indirect = read_exr_layer(image_path, "indirect", rw, rh);
    LayerComparison l = compare_layer("indirect", indirect, ref, c.width, c.height, block, exposure_stops);
    // A path-traced reference carries its own noise, which adds its expected relMSE to every comparison against it.
    if (exr_has_layer(reference_path, "indirect_variance")) {
      std::vector<float> variance = read_exr_layer(reference_path, "indirect_variance", rw, rh);
      double noise = 0.0;
      for (size_t i = 0; i < ref.size(); ++i)
        noise += variance[i] / (double(ref[i]) * ref[i] + kRelMseOffset) / double(ref.size());
      l.reference_noise = noise;
      if (l.block_rel_mse) l.block_reference_noise = block_rel_mse_of_noise(variance, ref, c.width, c.height, block);
    }
    c.layers.push_back(std::move(l));
  }
  return c;
}

nlohmann::json comparison_json(const ImageComparison& c) {
  nlohmann::json j = {{"image", c.image_path}, {"reference", c.reference_path}, {"block", c.block},
                      {"exposure", c.exposure_stops}, {"rendered_differently", c.rendered_differently},
                      {"finer_pixel_reference", c.finer_pixel_reference}};
  for (const LayerComparison& l : c.layers) {
    nlohmann::json layer = {{"rel_mse", l.pixel.rel_mse}, {"rmse", l.pixel.rmse}, {"mae", l.pixel.mae},
                            {"mean_flip", l.mean_flip}, {"mean_ratio", l.mean_ratio}};
    if (l.block_rel_mse) layer["block_rel_mse"] = *l.block_rel_mse;
    if (l.reference_noise) {
      layer["reference_noise"] = *l.reference_noise;
      layer["rel_mse_less_reference_noise"] = *l.rel_mse_less_reference_noise();
    }
    if (l.block_reference_noise) {
      layer["block_reference_noise"] = *l.block_reference_noise;
      layer["block_rel_mse_less_reference_noise"] = *l.block_rel_mse_less_reference_noise();
    }
    j[l.layer] = layer;
  }
  return j;
}

}  // namespace rcsplat
