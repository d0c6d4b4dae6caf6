// A size in bytes for messages: "12.3 MiB", "4.2 GiB".
#pragma once
#include <cstdio>
#include <string>

namespace rcsplat {

// unit: "MiB" or "GiB"; one decimal.
inline std::string byte_size(double bytes, const char* unit) {
  const double scale = unit[0] == 'G' ? double(1ull << 30) : double(1ull << 20);
  char text[48];
  std::snprintf(text, sizeof text, "%.1f %s", bytes / scale, unit);
  return text;
}

}  // namespace rcsplat
