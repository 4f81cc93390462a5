#include "raytrace/embree_scene.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadowcert::raytrace {

std::string_view build_mode_name(BuildMode mode) { return mode == BuildMode::robust ? "robust" : "fast"; }

EmbreeScene::EmbreeScene(const EmbreeDevice& device, const Soup& soup, BuildMode mode,
                         std::span<const std::uint8_t> select)
    : mode_(mode) {
  constexpr const char* kFunction = "embree_scene";
  require_indices_in_range(soup, kFunction);
  require_finite_vertices(soup, kFunction);
  if (!select.empty() && select.size() != soup.triangles.size())
    throw std::invalid_argument(std::string(kFunction) + ": select has " + std::to_string(select.size()) +
                                " flags for " + std::to_string(soup.triangles.size()) + " triangles");
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t v = 0; v < soup.vertices.size(); ++v)
    for (const double x : soup.vertices[v])
      if (!std::isfinite(static_cast<float>(x)))
        throw std::invalid_argument(std::string(kFunction) + ": vertex " + std::to_string(v) +
                                    " has a coordinate beyond float's range");
  triangles_.reserve(soup.triangles.size());
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    if (select.empty() || select[t] != 0) triangles_.push_back(static_cast<std::uint32_t>(t));

  scene_ = rtcNewScene(device.get());
  device.check(kFunction);
  // Released here on any throw below: the destructor does not run for a constructor that throws.
  try {
    const RTCBuildQuality quality = mode == BuildMode::robust ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
    rtcSetSceneFlags(scene_, mode == BuildMode::robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(scene_, quality);
    if (!triangles_.empty()) {
      RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
      device.check(kFunction);
      rtcSetGeometryBuildQuality(geometry, quality);
      // Embree pads the buffers it allocates itself (its vertex loads read 16 bytes).
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                   RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                   soup.vertices.size()));
      auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), triangles_.size()));
      if (vertices == nullptr || indices == nullptr) {
        rtcReleaseGeometry(geometry);
        device.check(kFunction);
        throw EmbreeError(std::string(kFunction) + ": rtcSetNewGeometryBuffer returned no buffer");
      }
      for (std::size_t v = 0; v < soup.vertices.size(); ++v)
        for (int k = 0; k < 3; ++k) vertices[3 * v + k] = static_cast<float>(soup.vertices[v][k]);
      for (std::size_t i = 0; i < triangles_.size(); ++i)
        for (int k = 0; k < 3; ++k) indices[3 * i + k] = soup.triangles[triangles_[i]][k];
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(scene_, geometry, 0);
      rtcReleaseGeometry(geometry);  // the scene holds it
    }
    rtcCommitScene(scene_);
    device.check(kFunction);
  } catch (...) {
    rtcReleaseScene(scene_);
    scene_ = nullptr;
    throw;
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EmbreeScene::~EmbreeScene() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
}

EmbreeScene::EmbreeScene(EmbreeScene&& other) noexcept
    : scene_(std::exchange(other.scene_, nullptr)),
      mode_(other.mode_),
      triangles_(std::move(other.triangles_)),
      build_seconds_(other.build_seconds_) {}

EmbreeScene& EmbreeScene::operator=(EmbreeScene&& other) noexcept {
  if (this != &other) {
    if (scene_ != nullptr) rtcReleaseScene(scene_);
    scene_ = std::exchange(other.scene_, nullptr);
    mode_ = other.mode_;
    triangles_ = std::move(other.triangles_);
    build_seconds_ = other.build_seconds_;
  }
  return *this;
}

}  // namespace shadowcert::raytrace
