// Small path helpers shared by the loaders and writers.
#pragma once
#include <cctype>
#include <filesystem>
#include <string>

namespace rcsplat {

// ".exr" for "Out.EXR": file formats are chosen by extension, whatever its case.
inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace rcsplat
