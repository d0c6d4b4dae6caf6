#include "image/denoiser.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "util/error.h"

namespace rcsplat {
namespace {

// The part of OIDN 2's C API (oidn.h, documented at openimagedenoise.org) that rcsplat calls, declared here because
// the library ships without headers. Handles are opaque pointers; enums are C ints.
using OidnDevice = void*;
using OidnFilter = void*;
using OidnBuffer = void*;
constexpr int kOidnDeviceTypeDefault = 0;
constexpr int kOidnErrorNone = 0;
constexpr int kOidnFormatFloat3 = 3;
constexpr int kOidnQualityHigh = 6;
const char* const kLibraryName = "libOpenImageDenoise.so.2";

const char* device_type_name(int type) {
  switch (type) {
    case 1: return "CPU";
    case 2: return "SYCL";
    case 3: return "CUDA";
    case 4: return "HIP";
    case 5: return "Metal";
    default: return "unknown";
  }
}

}  // namespace

struct Denoiser::Api {
  OidnDevice (*newDevice)(int type);
  void (*commitDevice)(OidnDevice);
  void (*releaseDevice)(OidnDevice);
  int (*getDeviceError)(OidnDevice, const char** message);
  int (*getDeviceInt)(OidnDevice, const char* name);
  OidnBuffer (*newBuffer)(OidnDevice, size_t bytes);
  void (*releaseBuffer)(OidnBuffer);
  void (*writeBuffer)(OidnBuffer, size_t offset, size_t bytes, const void* source);
  void (*readBuffer)(OidnBuffer, size_t offset, size_t bytes, void* destination);
  OidnFilter (*newFilter)(OidnDevice, const char* type);
  void (*releaseFilter)(OidnFilter);
  void (*setFilterImage)(OidnFilter, const char* name, OidnBuffer, int format, size_t width, size_t height,
                         size_t byte_offset, size_t pixel_byte_stride, size_t row_byte_stride);
  void (*setFilterBool)(OidnFilter, const char* name, bool value);
  void (*setFilterInt)(OidnFilter, const char* name, int value);
  void (*commitFilter)(OidnFilter);
  void (*executeFilter)(OidnFilter);
};

namespace {

template <typename F>
void bind_symbol(void* library, const std::string& path, const char* name, F*& function) {
  function = reinterpret_cast<F*>(dlsym(library, name));
  if (!function) throw Error(path + ": not Open Image Denoise 2 (no symbol " + name + ")");
}

}  // namespace

void Denoiser::check(const char* what) const {
  const char* message = nullptr;
  if (api_->getDeviceError(device_, &message) != kOidnErrorNone)
    throw Error(std::string("Open Image Denoise: ") + what + ": " + (message ? message : "unknown error"));
}

std::unique_ptr<Denoiser> Denoiser::load() {
  std::vector<std::string> candidates;
  if (const char* forced = std::getenv("RCSPLAT_OIDN_LIBRARY"); forced && *forced) {
    candidates.push_back(forced);
  } else {
    candidates.push_back(std::string(RCSPLAT_SOURCE_DIR) + "/build/oidn/lib/" + kLibraryName);
    candidates.push_back(kLibraryName);  // the system's library path, LD_LIBRARY_PATH included
  }
  std::string tried;
  void* library = nullptr;
  std::string path;
  for (const auto& candidate : candidates) {
    if (candidate.find('/') != std::string::npos && !std::filesystem::exists(candidate)) {
      tried += (tried.empty() ? " " : "; ") + candidate + ": no such file";
      continue;
    }
    library = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (library) {
      path = candidate;
      break;
    }
    const char* why = dlerror();
    tried += (tried.empty() ? " " : "; ") + candidate + ": " + (why ? why : "not loadable");
  }
  if (!library)
    throw Error("--denoise needs Intel Open Image Denoise 2, which was not found:" + tried +
                ". Install it with `bash scripts/install-oidn.sh` (the libraries of PyPI's pyoidn wheel), or set "
                "RCSPLAT_OIDN_LIBRARY to a libOpenImageDenoise.so.2");
  std::unique_ptr<Denoiser> denoiser(new Denoiser());
  denoiser->api_ = std::make_unique<Api>();
  Api& api = *denoiser->api_;
  bind_symbol(library, path, "oidnNewDevice", api.newDevice);
  bind_symbol(library, path, "oidnCommitDevice", api.commitDevice);
  bind_symbol(library, path, "oidnReleaseDevice", api.releaseDevice);
  bind_symbol(library, path, "oidnGetDeviceError", api.getDeviceError);
  bind_symbol(library, path, "oidnGetDeviceInt", api.getDeviceInt);
  bind_symbol(library, path, "oidnNewBuffer", api.newBuffer);
  bind_symbol(library, path, "oidnReleaseBuffer", api.releaseBuffer);
  bind_symbol(library, path, "oidnWriteBuffer", api.writeBuffer);
  bind_symbol(library, path, "oidnReadBuffer", api.readBuffer);
  bind_symbol(library, path, "oidnNewFilter", api.newFilter);
  bind_symbol(library, path, "oidnReleaseFilter", api.releaseFilter);
  bind_symbol(library, path, "oidnSetFilterImage", api.setFilterImage);
  bind_symbol(library, path, "oidnSetFilterBool", api.setFilterBool);
  bind_symbol(library, path, "oidnSetFilterInt", api.setFilterInt);
  bind_symbol(library, path, "oidnCommitFilter", api.commitFilter);
  bind_symbol(library, path, "oidnExecuteFilter", api.executeFilter);
  denoiser->device_ = api.newDevice(kOidnDeviceTypeDefault);
  if (!denoiser->device_) throw Error("Open Image Denoise (" + path + "): no device could be made");
  api.commitDevice(denoiser->device_);
  denoiser->check("making its device");
  denoiser->device_type_ = api.getDeviceInt(denoiser->device_, "type");
  return denoiser;
}

Denoiser::~Denoiser() {
  if (device_) api_->releaseDevice(device_);
  // The library stays loaded: OIDN's device modules keep threads (TBB's) that must not outlive their code.
}

std::string Denoiser::device_name() const { return device_type_name(device_type_); }

void Denoiser::denoise(std::vector<float>& rgb, int width, int height, const DenoiseGuides& guides) const {
  const size_t floats = size_t(width) * size_t(height) * 3;
  if (width <= 0 || height <= 0 || rgb.size() != floats) throw Error("denoise: the image is not width x height RGB");
  for (const auto* guide : {guides.albedo, guides.normal})
    if (guide && guide->size() != floats) throw Error("denoise: a guide image is not the colour's size");
  const Api& api = *api_;
  const size_t bytes = floats * sizeof(float);
  // Buffers on the device rather than shared host memory: a GPU device may not read host memory.
  struct Buffers {
    const Api& api;
    std::vector<OidnBuffer> held;
    ~Buffers() {
      for (OidnBuffer b : held)
        if (b) api.releaseBuffer(b);
    }
  } buffers{api, {}};
  auto upload = [&](const std::vector<float>& image) {
    OidnBuffer b = api.newBuffer(device_, bytes);
    buffers.held.push_back(b);
    check("allocating an image");
    std::vector<float> finite(image);
    for (float& v : finite)
      if (!std::isfinite(v)) v = 0.0f;
    api.writeBuffer(b, 0, bytes, finite.data());
    return b;
  };
  OidnFilter filter = api.newFilter(device_, "RT");
  check("making the RT filter");
  struct FilterHolder {
    const Api& api;
    OidnFilter f;
    ~FilterHolder() { api.releaseFilter(f); }
  } holder{api, filter};
  OidnBuffer color = upload(rgb);
  api.setFilterImage(filter, "color", color, kOidnFormatFloat3, width, height, 0, 0, 0);
  if (guides.albedo)
    api.setFilterImage(filter, "albedo", upload(*guides.albedo), kOidnFormatFloat3, width, height, 0, 0, 0);
  if (guides.normal)
    api.setFilterImage(filter, "normal", upload(*guides.normal), kOidnFormatFloat3, width, height, 0, 0, 0);
  OidnBuffer output = api.newBuffer(device_, bytes);
  buffers.held.push_back(output);
  api.setFilterImage(filter, "output", output, kOidnFormatFloat3, width, height, 0, 0, 0);
  api.setFilterBool(filter, "hdr", true);
  // The guides are the G-buffer's, averaged over each pixel's sub-pixels: noise-free, so OIDN need not prefilter them.
  api.setFilterBool(filter, "cleanAux", guides.albedo || guides.normal);
  api.setFilterInt(filter, "quality", kOidnQualityHigh);
  api.commitFilter(filter);
  check("setting up the RT filter");
  api.executeFilter(filter);
  check("denoising");
  api.readBuffer(output, 0, bytes, rgb.data());
  check("reading the result");
  for (float& v : rgb)
    if (!std::isfinite(v)) v = 0.0f;
}

}  // namespace rcsplat
