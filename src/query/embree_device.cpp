#include "query/embree_device.h"

#include <mutex>
#include <string>

#include "core/error.h"

namespace hm::query {
namespace {

// The last message of the error callback. Embree calls the callback on the thread of the failing
// API call; the mutex covers concurrent queries.
std::mutex g_message_mutex;
std::string g_last_message;

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unrecognised error";
}

// Called by Embree, so it must not throw: it only records.
void record_error(void* /*user*/, RTCError code, const char* message) noexcept {
  try {
    std::lock_guard<std::mutex> lock(g_message_mutex);
    g_last_message = std::string(error_name(code)) + (message ? std::string(": ") + message : "");
  } catch (...) {
    // Out of memory while recording: the error code itself is still pending on the device.
  }
}

struct DeviceHolder {
  RTCDevice device = nullptr;
  DeviceHolder() {
    device = rtcNewDevice(nullptr);
    if (device) rtcSetDeviceErrorFunction(device, record_error, nullptr);
  }
  ~DeviceHolder() {
    if (device) rtcReleaseDevice(device);
  }
};

}  // namespace

RTCDevice embree_device() {
  static DeviceHolder holder;
  if (!holder.device) {
    throw GeometryError("cannot create the Embree device: " +
                        std::string(error_name(rtcGetDeviceError(nullptr))));
  }
  return holder.device;
}

void check_embree(const char* what) {
  const RTCError code = rtcGetDeviceError(embree_device());
  if (code == RTC_ERROR_NONE) return;
  std::string message;
  {
    std::lock_guard<std::mutex> lock(g_message_mutex);
    message = g_last_message;
  }
  throw GeometryError(std::string("Embree failed in ") + what + " (" + error_name(code) + ")" +
                      (message.empty() ? "" : ": " + message));
}

}  // namespace hm::query
