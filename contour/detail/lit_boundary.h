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

[[nodiscard]] inline PointKey vertex_key(std::uint32_t v) { return {PointKey::vertex, v, v, 0}; }

[[nodiscard]] SilhouettePoint vertex_point(const SmoothCaster& c, std::uint32_t t, std::uint32_t v);

// The accurate point on edge k of triangle t (its corners' lit states differ) and its key,
// computed from the edge's lower vertex index to its higher one.
[[nodiscard]] std::pair<PointKey, SilhouettePoint> edge_point(const SmoothCaster& c,
                                                              std::span<const std::array<double, 3>> f,
                                                              std::uint32_t t, std::size_t k);

[[nodiscard]] LitBoundary accurate_boundary(const SmoothCaster& c, std::span<const std::array<double, 3>> f);
[[nodiscard]] LitBoundary discrete_boundary(const SmoothCaster& c, std::span<const std::uint8_t> lit_triangles);

[[nodiscard]] std::vector<KeyedLoop> chain(const LitBoundary& boundary);

[[nodiscard]] std::vector<SilhouetteLoop> loops_of(const LitBoundary& boundary, const std::vector<KeyedLoop>& keyed);

}  // namespace shadowcert::detail
