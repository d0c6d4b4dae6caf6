// The MP4 preview of a walkthrough's PNG frames, made by ffmpeg (H.264) when it is installed.
#pragma once
#include <string>

namespace rcsplat {

// ffmpeg's path on PATH, or "" when it is not installed.
std::string find_ffmpeg();

// Encodes frames first .. first + count - 1 of png_pattern (a printf pattern: frames/%04d.png) at fps into path,
// written beside it and renamed (util/atomic_file.h). Throws rcsplat::Error naming path when ffmpeg fails.
void encode_mp4(const std::string& ffmpeg, const std::string& png_pattern, long long first, long long count,
                double fps, const std::string& path);

}  // namespace rcsplat
