#pragma once
// Internal to contour/: the boundary of a caster's lit part as oriented pieces between named
// points (contour/silhouette_loop.h says what the pieces are), shared by the silhouette loops
// and the shadow volume built on them (contour/smooth_volume.h), so both name every point alike.
#include <array>
#include <compare>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "contour/silhouette_loop.h"
#include "contour/smooth_caster.h"

namespace shadowcert::detail {

// A loop point's name: a mesh vertex; the one point of a smooth edge (both triangles compute it
// alike); or the point of one side of a crease edge.
struct PointKey {
  enum Kind : std::uint8_t { vertex, smooth_edge, crease_side } kind = vertex;
  std::uint32_t a = 0, b = 0, side = 0;
  auto operator<=>(const PointKey&) const = default;
};

// An oriented piece of the boundary, with the lit part on its left. `triangle`: the triangle
// whose lit part it bounds (kBorder for the zero-length piece between a crease point's two
// copies).
struct Piece {
  PointKey from, to;
  std::uint32_t triangle = kBorder;
};

struct LitBoundary {
  std::vector<Piece> pieces;
  std::map<PointKey, SilhouettePoint> points;

  void add(const PointKey& from, const SilhouettePoint& p, const PointKey& to, const SilhouettePoint& q,
           std::uint32_t triangle);
};

// A loop as chained pieces: keys[i] -> keys[i + 1] is pieces[i] (a closed loop's last piece
// returns to keys[0], which is not repeated).
struct KeyedLoop {
  std::vector<PointKey> keys;
  std::vector<std::size_t> pieces;
  bool closed = false;
};

[[nodiscard]] inline bool lit(double f) { return f >= 0.0; }

// The corner values f = n . (l - w v) of a light, computed once per wedge (SmoothCaster::wedge:
// a silhouette pass touches every triangle but most only to see one sign at all three corners,
// so the pass is memory-bound and the wedges are a third of the corners on a smooth mesh). The
// same expression, so the same bits, as corner_light_values.
class CornerValues {
 public:
  CornerValues(const SmoothCaster& caster, const Light& light) : caster_(&caster), f_(caster.wedge_vertex.size()) {
    const auto& l = light.position;
    for (std::size_t w = 0; w < f_.size(); ++w) {
      const Vec3& v = caster.vertices[caster.wedge_vertex[w]];
      const Vec3& n = caster.wedge_normal[w];
      f_[w] = n[0] * (l[0] - l[3] * v[0]) + n[1] * (l[1] - l[3] * v[1]) + n[2] * (l[2] - l[3] * v[2]);
    }
  }
  [[nodiscard]] std::array<double, 3> operator[](std::size_t t) const {
    const auto& w = caster_->wedge[t];
    return {f_[w[0]], f_[w[1]], f_[w[2]]};
  }

 private:
  const SmoothCaster* caster_;
  std::vector<double> f_;
};

[[nodiscard]] inline PointKey vertex_key(std::uint32_t v) { return {PointKey::vertex, v, v, 0}; }

[[nodiscard]] SilhouettePoint vertex_point(const SmoothCaster& c, std::uint32_t t, std::uint32_t v);

// The accurate point on edge k of triangle t (its corners' lit states differ) and its key,
// computed from the edge's lower vertex index to its higher one.
[[nodiscard]] std::pair<PointKey, SilhouettePoint> edge_point(const SmoothCaster& c, const CornerValues& f,
                                                              std::uint32_t t, std::size_t k);

[[nodiscard]] LitBoundary accurate_boundary(const SmoothCaster& c, const CornerValues& f);
[[nodiscard]] LitBoundary discrete_boundary(const SmoothCaster& c, std::span<const std::uint8_t> lit_triangles);

[[nodiscard]] std::vector<KeyedLoop> chain(const LitBoundary& boundary);

[[nodiscard]] std::vector<SilhouetteLoop> loops_of(const LitBoundary& boundary, const std::vector<KeyedLoop>& keyed);

}  // namespace shadowcert::detail
