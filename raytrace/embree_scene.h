#pragma once
// A soup's triangles as one Embree scene: its BVH over the float-rounded vertices, in the fast
// or the robust mode (docs/ray-tracing.md#modes). Move-only owner of the RTCScene.
//
//   raytrace::EmbreeDevice device;
//   raytrace::EmbreeScene scene(device, soup, raytrace::BuildMode::robust);   // every triangle
//   raytrace::EmbreeScene casters(device, soup, raytrace::BuildMode::fast, casts);  // casts[t] != 0
//   rtcIntersect1(scene.get(), &context, &rayhit);  // rayhit.hit.primID: scene.triangle(primID)
//
// The vertices are rounded once to float (as the GL methods receive them): Embree traces float
// rays against float triangles; nothing here is exact.
#include <embree3/rtcore.h>

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/soup.h"
#include "raytrace/embree_device.h"

namespace shadowcert::raytrace {

// Embree's two ways of building and traversing:
//   fast    RTC_BUILD_QUALITY_MEDIUM, no scene flag: Embree's default, what a renderer uses;
//   robust  RTC_SCENE_FLAG_ROBUST (traversal and the triangle test avoid the optimisations
//           that may let a ray pass between two triangles sharing an edge) and
//           RTC_BUILD_QUALITY_HIGH (a spatial-split SAH BVH: slower to build, faster to trace).
enum class BuildMode { fast, robust };

// "fast", "robust".
[[nodiscard]] std::string_view build_mode_name(BuildMode mode);

class EmbreeScene {
 public:
  // The triangles of `soup` whose flag in `select` is nonzero (empty: every triangle), one
  // geometry (id 0) whose primitive i is soup triangle triangle(i). Throws
  // std::invalid_argument("embree_scene: ...") for an index out of range, a non-finite
  // coordinate or one beyond float's range, or `select` neither empty nor one flag per
  // triangle; EmbreeError("embree_scene: ...") with Embree's message when Embree fails.
  EmbreeScene(const EmbreeDevice& device, const Soup& soup, BuildMode mode, std::span<const std::uint8_t> select = {});
  ~EmbreeScene();
  EmbreeScene(EmbreeScene&& other) noexcept;
  EmbreeScene& operator=(EmbreeScene&& other) noexcept;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  [[nodiscard]] RTCScene get() const { return scene_; }
  [[nodiscard]] BuildMode mode() const { return mode_; }
  // The soup index of Embree's primitive `primitive` (hit.primID).
  [[nodiscard]] std::uint32_t triangle(std::uint32_t primitive) const { return triangles_[primitive]; }
  [[nodiscard]] std::size_t size() const { return triangles_.size(); }
  // Wall seconds of the build (buffers filled, rtcCommitScene), in the calling thread's TBB arena.
  [[nodiscard]] double build_seconds() const { return build_seconds_; }

 private:
  RTCScene scene_ = nullptr;
  BuildMode mode_ = BuildMode::fast;
  std::vector<std::uint32_t> triangles_;
  double build_seconds_ = 0.0;
};

}  // namespace shadowcert::raytrace
