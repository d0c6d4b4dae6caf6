#include <cstdio>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "util/atomic_file.h"
#include "image/comparison.h"
#include "image/flip.h"
#include "image/image_io.h"
#include "util/error.h"

namespace rcsplat {

int run_compare(const CompareOptions& o) {
  const ImageComparison c = compare_exr_files(o.image_path, o.reference_path, o.block, o.exposure);
  const std::string block_name = std::to_string(o.block) + "x" + std::to_string(o.block) + " relMSE";
  std::printf("%-10s %-12s %-12s %-12s %-14s %-8s %s\n", "layer", "relMSE", "RMSE", "MAE", block_name.c_str(), "FLIP",
              "mean/ref");
  for (const LayerComparison& l : c.layers) {
    char block[32] = "-";
    if (l.block_rel_mse) std::snprintf(block, sizeof block, "%.4e", *l.block_rel_mse);
    std::printf("%-10s %-12.4e %-12.4e %-12.4e %-14s %-8.4f %.4f\n", l.layer.c_str(), l.pixel.rel_mse, l.pixel.rmse,
                l.pixel.mae, block, l.mean_flip, l.mean_ratio);
  }
  if (!c.find("indirect")) std::printf("indirect   (no indirect layer in both images)\n");
  if (const LayerComparison* l = c.find("indirect"); l && l->reference_noise) {
    std::printf("reference noise: expected indirect relMSE %.4e (from its variance); relMSE less that: %.4e\n",
                *l->reference_noise, l->pixel.rel_mse - *l->reference_noise);
    if (l->block_reference_noise)
      std::printf("reference noise: expected indirect %s %.4e; %s less that: %.4e\n", block_name.c_str(),
                  *l->block_reference_noise, block_name.c_str(), *l->block_rel_mse - *l->block_reference_noise);
  }
  std::printf("FLIP: mean LDR-FLIP (0 = identical, 1 = most different) of the images tone-mapped as the PNGs are, "
              "exposure %+g stops, 67 pixels per degree\n", double(o.exposure));
  const LayerComparison& judged = c.find("indirect") && o.heatmap_layer == "indirect" ? *c.find("indirect") : c.layers[0];
  if (!o.heatmap_path.empty()) {
    std::vector<double> rel(judged.rel_mse_map.begin(), judged.rel_mse_map.end());
    write_png_display(o.heatmap_path, c.width, c.height, error_heatmap(rel));
    std::printf("wrote      %s (%s layer: per-pixel relMSE, log scale: dark blue 1e-6 ... white 1)\n",
                o.heatmap_path.c_str(), judged.layer.c_str());
  }
  if (!o.flip_heatmap_path.empty()) {
    write_png_display(o.flip_heatmap_path, c.width, c.height, flip_heatmap(judged.flip_map));
    std::printf("wrote      %s (%s layer: per-pixel FLIP, magma: black 0 ... pale yellow 1)\n",
                o.flip_heatmap_path.c_str(), judged.layer.c_str());
  }
  if (!o.json_path.empty()) write_text_file(o.json_path, comparison_json(c).dump(2) + "\n");
  return 0;
}

Command add_compare_command(CLI::App& app, const HelpGroups&) {
  auto o = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Error of an image against a reference: relMSE, RMSE, MAE, relMSE of block means, FLIP");
  cmd->add_option("image", o->image_path, "The image to judge (.exr)")->required();
  cmd->add_option("reference", o->reference_path, "The reference (.exr)")->required();
  cmd->add_option("--heatmap", o->heatmap_path, "Write a false-colour per-pixel relMSE image (.png)");
  cmd->add_option("--flip-heatmap", o->flip_heatmap_path, "Write the per-pixel FLIP image (.png, magma)");
  cmd->add_option("--heatmap-layer", o->heatmap_layer, "Layer the heat maps show: full (default) or indirect")
      ->check(CLI::IsMember({"full", "indirect"}));
  cmd->add_option("--exposure", o->exposure, "Exposure in stops of the tone mapping FLIP judges (as for PNGs)");
  cmd->add_option("--json", o->json_path, "Also write the numbers as JSON");
  cmd->add_option("--block", o->block,
                  "Also relMSE of BxB pixel means (default " + std::to_string(CompareOptions{}.block) +
                      "): noise averages out, a cache's blotches do not")
      ->check(CLI::Range(1, 4096));
  return {cmd, [o] { return run_compare(*o); }};
}

}  // namespace rcsplat
