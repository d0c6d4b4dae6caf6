// `rcsplat flicker`: how much a frame sequence's light changes between consecutive frames where both see the same
// surface (image/flicker.h), and how much of that a reference sequence of the same path shows too.
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "image/flicker.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/frame_pattern.h"
#include "util/log.h"

namespace rcsplat {
namespace {

struct SequencePairs {
  std::vector<TemporalError> pairs;
  double mean = 0.0;
};

SequencePairs sequence_flicker(const FramePattern& pattern, const FramePattern* geometry, long long first,
                               long long last, const std::string& layer, bool demodulate) {
  SequencePairs out;
  auto read = [&](long long f) {
    return read_sequence_frame(pattern.path(f), layer, geometry ? geometry->path(f) : "", demodulate);
  };
  SequenceFrame earlier = read(first);
  for (long long f = first + 1; f <= last; ++f) {
    SequenceFrame later = read(f);
    out.pairs.push_back(temporal_rel_mse(earlier, later));
    out.mean += out.pairs.back().rel_mse;
    earlier = std::move(later);
  }
  out.mean /= double(out.pairs.size());
  return out;
}

}  // namespace

int run_flicker(const FlickerOptions& o) {
  const FramePattern frames(o.frames, "flicker");
  const std::string layer = o.layer == "full" ? "" : o.layer;
  long long last = o.last_frame;
  if (last < 0) {
    last = o.first_frame;
    while (std::filesystem::exists(frames.path(last + 1))) ++last;
  }
  if (last <= o.first_frame)
    throw Error("flicker: " + frames.path(o.first_frame + 1) + " is missing: a sequence needs two frames or more");
  for (long long f = o.first_frame; f <= last; ++f)
    if (!std::filesystem::exists(frames.path(f))) throw Error("flicker: " + frames.path(f) + " is missing");
  if (!o.json_path.empty()) check_writable_destination(o.json_path);
  std::optional<FramePattern> positions;
  if (!o.positions.empty()) positions.emplace(o.positions, "--positions");
  const SequencePairs judged =
      sequence_flicker(frames, positions ? &*positions : nullptr, o.first_frame, last, layer, o.demodulate);
  SequencePairs reference;
  if (!o.reference.empty())
    reference =
        sequence_flicker(FramePattern(o.reference, "--reference"), nullptr, o.first_frame, last, layer, o.demodulate);
  double seen = 0.0;
  for (const TemporalError& p : judged.pairs) seen += p.hits ? double(p.pixels) / double(p.hits) : 0.0;
  seen /= double(judged.pairs.size());
  std::printf("frames       %s, %lld to %lld (%zu pairs), layer %s%s\n", o.frames.c_str(), o.first_frame, last,
              judged.pairs.size(), o.layer.c_str(), o.demodulate ? " over the albedo" : "");
  std::printf(
      "flicker      temporal relMSE %.4g (mean over the pairs); %.1f%% of the pixels that see a surface saw it "
      "in the frame before too\n",
      judged.mean, 100.0 * seen);
  if (!o.reference.empty())
    std::printf("reference    %s: %.4g; less the reference's: %.4g\n", o.reference.c_str(), reference.mean,
                judged.mean - reference.mean);
  if (!o.json_path.empty()) {
    nlohmann::json pairs = nlohmann::json::array();
    for (size_t i = 0; i < judged.pairs.size(); ++i) {
      nlohmann::json p = {{"frame", o.first_frame + (long long)i + 1},
                          {"rel_mse", judged.pairs[i].rel_mse},
                          {"pixels", judged.pairs[i].pixels}};
      if (!o.reference.empty()) p["reference_rel_mse"] = reference.pairs[i].rel_mse;
      pairs.push_back(p);
    }
    nlohmann::json j = {{"frames", o.frames}, {"first_frame", o.first_frame}, {"last_frame", last},
                        {"layer", o.layer},   {"demodulated", o.demodulate},  {"temporal_rel_mse", judged.mean},
                        {"pairs", pairs}};
    if (!o.reference.empty()) {
      j["reference"] = o.reference;
      j["reference_temporal_rel_mse"] = reference.mean;
      j["temporal_rel_mse_less_reference"] = judged.mean - reference.mean;
    }
    write_text_file(o.json_path, j.dump(2) + "\n");
  }
  return 0;
}

Command add_flicker_command(CLI::App& app, const HelpGroups&) {
  auto o = std::make_shared<FlickerOptions>();
  CLI::App* cmd =
      app.add_subcommand("flicker",
                         "How much a frame sequence's light changes between consecutive frames where both see the same "
                         "surface (temporal relMSE after reprojection by the position layer), less a reference's");
  cmd->add_option("frames", o->frames, "The frames, as animate wrote them (.exr pattern: frames/%04d.exr)")->required();
  cmd->add_option("--reference", o->reference,
                  "A reference sequence of the same path (pattern): its own flicker is subtracted");
  cmd->add_option("--positions", o->positions,
                  "Take each frame's position, depth and camera from this sequence (pattern) of the same frames: for "
                  "a denoised sequence, whose EXRs hold only colours");
  cmd->add_option("--first-frame", o->first_frame, "First frame (default 0)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--last-frame", o->last_frame, "Last frame (default: up to the first missing one)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--layer", o->layer, "Layer judged: indirect (default) or full")
      ->check(CLI::IsMember({"indirect", "full"}));
  cmd->add_flag("--demodulate", o->demodulate,
                "Judge the layer divided by the albedo layer (pixels of albedo below 0.02 left out): textures do not "
                "flicker, but the nearest pixel does not reproject them exactly either");
  cmd->add_option("--json", o->json_path, "Also write the numbers, a pair of frames each, as JSON");
  return {cmd, [o] { return run_flicker(*o); }};
}

}  // namespace rcsplat
