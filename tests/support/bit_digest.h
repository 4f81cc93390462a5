#pragma once
// FNV-1a over the bytes of values, in the order added: a pinned fingerprint of outputs that
// must be the same bit for bit (exact images, a seed's generated case) on every machine.
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "core/pixel_ray.h"
#include "core/camera.h"
#include "core/light.h"
#include "core/soup.h"

namespace shadowcert::test {

class BitDigest {
 public:
  template <typename T>
  void add(const std::vector<T>& values) {
    add_bytes(values.size());
    for (const T& v : values) add_bytes(v);
  }
  template <typename T>
  void add_value(const T& value) {
    add_bytes(value);
  }
  void add(const Soup& soup) {
    add(soup.vertices);
    add(soup.triangles);
    add(soup.normals);
  }
  void add(const Light& light) { add_value(light.position); }
  // The camera and the frame the exact image's rays come from (core/pixel_ray.h).
  void add(const Camera& camera) {
    add_value(camera.eye);
    add_value(camera.target);
    add_value(camera.up);
    add_value(camera.fov_y_degrees);
    add_value(camera.near_plane);
    const CameraFrame frame = camera_frame(camera);
    add_value(frame.right);
    add_value(frame.up);
    add_value(frame.forward);
    add_value(frame.half_width);
    add_value(frame.half_height);
  }
  [[nodiscard]] std::string hex() const {
    std::ostringstream out;
    out << std::hex << state_;
    return out.str();
  }

 private:
  template <typename T>
  void add_bytes(const T& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t k = 0; k < sizeof(T); ++k) state_ = (state_ ^ bytes[k]) * 0x100000001b3ULL;
  }
  std::uint64_t state_ = 0xcbf29ce484222325ULL;
};

}  // namespace shadowcert::test
