// Intel Open Image Denoise (OIDN 2), loaded at run time: rcsplat builds and runs without it, and only `--denoise`
// needs it. Debian 12 has no package; scripts/install-oidn.sh puts the libraries of PyPI's pyoidn wheel in
// build/oidn/lib. The part of OIDN's documented C API used here is declared in denoiser.cpp.
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace rcsplat {

// What OIDN's RT filter is given beside the noisy image. Both optional (empty): albedo and normal images the same
// size as the colour, noise-free (rcsplat's G-buffer layers), which let the filter keep texture and geometric edges.
struct DenoiseGuides {
  const std::vector<float>* albedo = nullptr;
  const std::vector<float>* normal = nullptr;
};

class Denoiser {
 public:
  // Loads the library and makes a device (OIDN's default: a GPU it supports, else the CPU). Where it looks, in turn:
  // $RCSPLAT_OIDN_LIBRARY (a path to libOpenImageDenoise.so.2: then only there), the folder scripts/install-oidn.sh
  // fills in this build (build/oidn/lib), and the system's library path. Throws rcsplat::Error saying what is
  // missing and how to install it.
  static std::unique_ptr<Denoiser> load();
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  // The RT filter at high quality on a linear HDR image (three floats a pixel, row-major), in place. Non-finite
  // input values are taken as 0 (OIDN's contract wants finite input); the output is finite.
  void denoise(std::vector<float>& rgb, int width, int height, const DenoiseGuides& guides) const;

  std::string device_name() const;  // "CPU", "CUDA", ...

 private:
  struct Api;
  Denoiser() = default;
  // Throws with OIDN's own message when the device holds an error (OIDN reports errors per device, not per call).
  void check(const char* what) const;
  std::unique_ptr<Api> api_;  // the library stays loaded for the process (~Denoiser)
  void* device_ = nullptr;
  int device_type_ = 0;
};

}  // namespace rcsplat
