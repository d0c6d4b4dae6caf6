#include "bvh/embree_device.h"

#include <string>

#include "util/error.h"
#include "util/log.h"

namespace rcsplat {
namespace {
void report_error(void*, RTCError code, const char* message) {
  log_warning("Embree error " + std::to_string(int(code)) + ": " + (message ? message : ""));
}
}  // namespace

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw Error("cannot create an Embree device (rtcNewDevice failed)");
    rtcSetDeviceErrorFunction(d, report_error, nullptr);
    return d;
  }();
  return device;
}

}  // namespace rcsplat
