#include "passes/sample_rounds.h"

#include <algorithm>
#include <cmath>

#include "image/error_metrics.h"

namespace rcsplat {

namespace {

// A pixel's level at threshold t: the doublings whose gain per chunk, e / (2 a 4^L), is at least t.
unsigned level_at(double gain_per_chunk, double t, unsigned max_level) {
  unsigned level = 0;
  while (level < max_level && gain_per_chunk >= t) {
    ++level;
    gain_per_chunk /= 4.0;
  }
  return level;
}

}  // namespace

std::vector<uint8_t> refinement_levels(const std::vector<cl_float4>& errors, int width, int height,
                                              double extra_chunks, unsigned max_level) {
  const size_t pixels = size_t(width) * size_t(height);
  std::vector<uint8_t> levels(pixels, 0);
  if (errors.size() != pixels || !(extra_chunks >= 1.0)) return levels;
  // Gain per chunk of each refined pixel's first doubling, e / (2 a), from its neighbours' samples alone.
  std::vector<double> first_gain(pixels, 0.0);
  double highest = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t at = size_t(y) * size_t(width) + size_t(x);
      const cl_float4& own = errors[at];
      if (!(own.s[2] > 0.0f)) continue;
      double variance = 0.0, sampled = 0.0, neighbours = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const cl_float4& e = errors[size_t(ny) * size_t(width) + size_t(nx)];
          if (!(e.s[2] > 0.0f) || !std::isfinite(e.s[0]) || !std::isfinite(e.s[3])) continue;
          variance += double(e.s[0]);
          sampled += double(e.s[3]);
          neighbours += 1.0;
        }
      if (!(neighbours > 0.0)) continue;
      const double luminance = (std::isfinite(own.s[1]) ? double(own.s[1]) : 0.0) + sampled / neighbours;
      const double relative = variance / neighbours / (luminance * luminance + kRelMseOffset);
      first_gain[at] = relative / (2.0 * double(own.s[2]));
      highest = std::max(highest, first_gain[at]);
    }
  if (!(highest > 0.0) || !std::isfinite(highest)) return levels;
  auto cost = [&](double t) {
    double chunks = 0.0;
    for (size_t i = 0; i < pixels; ++i)
      if (first_gain[i] >= t)
        chunks += double(errors[i].s[2]) * (std::exp2(double(level_at(first_gain[i], t, max_level))) - 1.0);
    return chunks;
  };
  // The lowest threshold (most doublings) whose cost fits, by bisection on log2(t): cost falls as t rises.
  double affordable = std::log2(highest) + 1.0, too_low = std::log2(highest) - 4.0 * double(max_level) - 64.0;
  if (cost(std::exp2(too_low)) <= extra_chunks) {
    affordable = too_low;
  } else {
    for (int step = 0; step < 60; ++step) {
      const double mid = 0.5 * (affordable + too_low);
      (cost(std::exp2(mid)) <= extra_chunks ? affordable : too_low) = mid;
    }
  }
  const double t = std::exp2(affordable);
  for (size_t i = 0; i < pixels; ++i)
    if (first_gain[i] >= t) levels[i] = uint8_t(level_at(first_gain[i], t, max_level));
  return levels;
}

RoundsPlan plan_rounds(const std::vector<cl_float4>& errors, int width, int height,
                       double chunks_per_sampled_sub_pixel) {
  RoundsPlan plan;
  for (const cl_float4& e : errors) plan.sampled_sub_pixels += uint64_t(e.s[2]);
  plan.levels = refinement_levels(errors, width, height,
                                  (chunks_per_sampled_sub_pixel - 1.0) * double(plan.sampled_sub_pixels));
  plan.chunks = plan.sampled_sub_pixels + chunks_added(plan.levels, errors);
  for (uint8_t level : plan.levels) plan.refined_pixels += level > 0;
  return plan;
}

uint64_t chunks_added(const std::vector<uint8_t>& levels, const std::vector<cl_float4>& errors) {
  uint64_t chunks = 0;
  for (size_t o = 0; o < levels.size() && o < errors.size(); ++o)
    chunks += uint64_t(errors[o].s[2]) * ((uint64_t(1) << levels[o]) - 1);
  return chunks;
}

unsigned run_later_rounds(
    const std::vector<uint8_t>& levels,
    const std::function<void(const std::vector<cl_uint>& listed, unsigned first_chunk, unsigned chunks)>& run_round) {
  unsigned rounds = 1;
  for (unsigned round = 1; round <= kRoundsMaxLevel; ++round) {
    std::vector<cl_uint> listed;
    for (size_t o = 0; o < levels.size(); ++o)
      if (levels[o] >= round) listed.push_back(cl_uint(o));
    if (listed.empty()) break;
    run_round(listed, 1u << (round - 1), 1u << (round - 1));
    rounds = round + 1;
  }
  return rounds;
}

}  // namespace rcsplat
