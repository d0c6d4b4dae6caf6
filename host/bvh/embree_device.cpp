#include "bvh/embree_device.h"

#include <mutex>

#include "util/error.h"

namespace rcsplat {
namespace {

std::mutex error_mutex;
std::string pending_error;  // the first message the callback received since the last check

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_UNKNOWN: return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
  }
  return "error";
}

void record_error(void*, RTCError code, const char* message) {
  std::lock_guard<std::mutex> lock(error_mutex);
  if (pending_error.empty()) pending_error = std::string(error_name(code)) + (message && *message ? ": " + std::string(message) : "");
}

}  // namespace

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw Error("cannot create an Embree device (rtcNewDevice failed: " + std::string(error_name(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(d, record_error, nullptr);
    return d;
  }();
  return device;
}

void check_embree(const std::string& what) {
  RTCError code = rtcGetDeviceError(embree_device());
  std::string message;
  {
    std::lock_guard<std::mutex> lock(error_mutex);
    message.swap(pending_error);
  }
  if (code == RTC_ERROR_NONE && message.empty()) return;
  throw Error("Embree: " + what + " failed: " + (message.empty() ? std::string(error_name(code)) : message));
}

}  // namespace rcsplat
