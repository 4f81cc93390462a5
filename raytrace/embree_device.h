#pragma once
// An Embree device (RTCDevice) owned by one object, and the errors Embree reports turned into
// exceptions that carry Embree's own message (docs/ray-tracing.md).
//
// Embree reports an error through a callback (and rtcGetDeviceError); a C++ exception must not
// unwind through Embree's C interface, so the callback only records the message, and every
// wrapper call checks it afterwards (check()), throwing EmbreeError("<function>: <Embree's
// message>").
//
//   raytrace::EmbreeDevice device;                 // rtcNewDevice, the error callback set
//   RTCScene s = rtcNewScene(device.get());
//   device.check("embree_scene");                  // throws if Embree reported an error
#include <embree3/rtcore.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace shadowcert::raytrace {

// What Embree reported: its error code's name and its message, after the function's name.
class EmbreeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Move-only owner of an RTCDevice (rtcReleaseDevice on destruction). Not thread-safe to
// check() from several threads at once; the ray tracing below checks once per stage.
class EmbreeDevice {
 public:
  // Throws EmbreeError("EmbreeDevice: ...") when Embree cannot create a device (an unsupported
  // CPU, a bad configuration string: Embree's rtcNewDevice config, e.g. "verbose=1").
  explicit EmbreeDevice(std::string_view config = {});
  ~EmbreeDevice();
  EmbreeDevice(EmbreeDevice&& other) noexcept;
  EmbreeDevice& operator=(EmbreeDevice&& other) noexcept;
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  [[nodiscard]] RTCDevice get() const { return device_; }
  // Throws EmbreeError("<function>: <code>: <message>") when Embree reported an error since the
  // last check (the first one reported), and clears it.
  void check(std::string_view function) const;

 private:
  // The callback's record; a stable address for Embree's user pointer across moves.
  struct ErrorRecord {
    std::string first;  // empty: no error since the last check
  };
  RTCDevice device_ = nullptr;
  std::unique_ptr<ErrorRecord> errors_;
};

}  // namespace shadowcert::raytrace
