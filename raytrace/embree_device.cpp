#include "raytrace/embree_device.h"

#include <string>
#include <utility>

namespace shadowcert::raytrace {
namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
  }
  return "RTC_ERROR (unknown code)";
}

}  // namespace

EmbreeDevice::EmbreeDevice(std::string_view config) : errors_(std::make_unique<ErrorRecord>()) {
  const std::string text(config);
  device_ = rtcNewDevice(text.empty() ? nullptr : text.c_str());
  if (device_ == nullptr) {
    // No device to ask through the callback: the error is the thread's (rtcGetDeviceError(NULL)).
    const RTCError code = rtcGetDeviceError(nullptr);
    throw EmbreeError(std::string("EmbreeDevice: rtcNewDevice failed: ") + error_name(code) +
                      (text.empty() ? std::string() : " (config '" + text + "')"));
  }
  rtcSetDeviceErrorFunction(
      device_,
      [](void* user, RTCError code, const char* message) {
        auto* record = static_cast<ErrorRecord*>(user);
        if (record->first.empty())
          record->first = std::string(error_name(code)) + ": " + (message != nullptr ? message : "(no message)");
      },
      errors_.get());
}

EmbreeDevice::~EmbreeDevice() {
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

EmbreeDevice::EmbreeDevice(EmbreeDevice&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)), errors_(std::move(other.errors_)) {}

EmbreeDevice& EmbreeDevice::operator=(EmbreeDevice&& other) noexcept {
  if (this != &other) {
    if (device_ != nullptr) rtcReleaseDevice(device_);
    device_ = std::exchange(other.device_, nullptr);
    errors_ = std::move(other.errors_);
  }
  return *this;
}

void EmbreeDevice::check(std::string_view function) const {
  if (errors_ == nullptr) throw EmbreeError(std::string(function) + ": the Embree device was moved from");
  if (errors_->first.empty()) return;
  const std::string message = std::move(errors_->first);
  errors_->first.clear();
  throw EmbreeError(std::string(function) + ": " + message);
}

}  // namespace shadowcert::raytrace
