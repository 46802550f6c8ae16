#include "base/embree_device.h"

#include <cstdio>
#include <stdexcept>

namespace bounce {
namespace {

void report_embree_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

}  // namespace

RTCDevice embree_device() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw std::runtime_error("embree: cannot create a device");
    rtcSetDeviceErrorFunction(d, report_embree_error, nullptr);
    return d;
  }();
  return device;
}

}  // namespace bounce
