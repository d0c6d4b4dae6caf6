// A walkthrough's statistics file (--stats): a CSV row a frame with its time per pass, records, rays and memory.
#pragma once
#include <cstddef>
#include <string>

#include "render/frame.h"

namespace rcsplat {

// One rendered frame: its number, time on the path and statistics.
struct FrameRow {
  long long frame = 0;
  double time = 0.0;
  RenderStats stats;
  size_t host_peak_bytes = 0;
};

// The CSV's first line, and a frame's line (both end in a newline).
extern const char* const kFrameTableHeader;
std::string frame_table_row(const FrameRow& row);

}  // namespace rcsplat
