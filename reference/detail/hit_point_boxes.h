#pragma once
// Internal to reference/exact_image.cpp: per ray, a box enclosing the point P where the ray first
// meets a triangle, kept once as the ray is traced and read by the footprint tests and the counts
// (each test on P is exact whatever the box, which only filters).
//
// Stored as floats rounded outward (core/outward_float.h) when the scene's coordinates allow it,
// else as doubles. A float box is looser, by about 2^-22 of the coordinates' magnitude: far inside
// a pixel's footprint, so the filters decide as before. It takes 24 bytes a ray, not 48: at
// 1024x768 with the corner rays, 38 MB less of the fresh memory whose first touch this
// virtual machine pays about 1 ms per MB for (docs/diff.md, "What the exact image touches").
//
// A hit point lies on a triangle, so inside the box of the scene's vertices: each stored box is
// cut to that box first, which keeps it finite (a HitPoint box of a grazing ray can be wide) and
// still encloses P. The scene qualifies when its largest coordinate magnitude M is within
// [kLeastFloatScale, kMostFloatScale]: above, a float may overflow; below, the float's absolute
// step (2^-149) is no longer small beside M.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "core/box.h"
#include "core/huge_page_advice.h"
#include "core/outward_float.h"

namespace shadowcert::detail {

inline constexpr double kMostFloatScale = 0x1p100;
inline constexpr double kLeastFloatScale = 0x1p-100;

class HitPointBoxes {
 public:
  using Box = std::array<Vec3, 2>;  // {lo, hi}, lo <= hi axis by axis

  // `rays` entries, none set; `scene`: the box of the scene's vertices.
  HitPointBoxes(std::size_t rays, const shadowcert::Box& scene) : scene_(scene) {
    double scale = 0.0;
    for (std::size_t a = 0; a < 3; ++a) scale = std::max({scale, std::fabs(scene.lo[a]), std::fabs(scene.hi[a])});
    in_float_ = kLeastFloatScale <= scale && scale <= kMostFloatScale;
    if (in_float_)
      floats_ = HugePageBuffer<FloatBox>(rays);
    else
      doubles_ = HugePageBuffer<Box>(rays);
  }

  // Precondition: `box` encloses a point of the scene's box. Entries of distinct rays may be set
  // from several threads at once.
  void set(std::size_t ray, const Box& box) {
    if (!in_float_) {
      doubles_[ray] = box;
      return;
    }
    FloatBox& f = floats_[ray];
    for (std::size_t a = 0; a < 3; ++a) {
      f.lo[a] = round_down_to_float(std::max(box[0][a], scene_.lo[a]));
      f.hi[a] = round_up_to_float(std::min(box[1][a], scene_.hi[a]));
    }
  }

  // The box of a ray whose entry was set.
  [[nodiscard]] Box operator[](std::size_t ray) const {
    if (!in_float_) return doubles_[ray];
    const FloatBox& f = floats_[ray];
    return {Vec3{f.lo[0], f.lo[1], f.lo[2]}, Vec3{f.hi[0], f.hi[1], f.hi[2]}};
  }

  [[nodiscard]] bool in_float() const { return in_float_; }

 private:
  struct FloatBox {
    std::array<float, 3> lo, hi;
  };
  shadowcert::Box scene_;
  bool in_float_ = false;
  HugePageBuffer<FloatBox> floats_;
  HugePageBuffer<Box> doubles_;
};

}  // namespace shadowcert::detail
