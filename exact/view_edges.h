#pragma once
// The edges of a soup as an eye sees them, exact (docs/edge-maps.md#the-exact-ground-truth; Nienhaus and
// Doellner 2003, section 3, written for soups): per edge of the canonical soup's edge table
// (scene/canonical_soup.h, scene/edge_table.h), which of the three classes it belongs to.
//
//   silhouette : the edge's exact multiplicity with the eye in place of the light (a point
//                light at the eye, exact/edge_multiplicity.h) is nonzero:
//                m(u, v) = - sum over triangles {u, v, o} with orient(u, v, o, eye) != 0 of
//                that sign. On a consistently oriented manifold edge this is the paper's
//                silhouette (one face towards the eye, one away: m = +-2); on a soup it needs
//                no orientation: a border edge of a triangle not seen edge-on has m = +-1, a
//                fan of k triangles has m of k's parity.
//   border     : exactly one proper triangle on the edge.
//   crease     : exactly two proper triangles, both seen from the eye (orient(u, v, o, eye) !=
//                0 for both) with m = 0, i.e. their third vertices lie strictly on opposite
//                sides of the plane through the eye and the edge: on a consistently oriented
//                edge, both faces towards the eye or both away; and their bend angle
//                (exact/normal_angle.h) strictly above the threshold.
//
// A proper triangle has three distinct, non-collinear vertices (exact/degenerate_triangles.h);
// a degenerate one (collinear, or a repeated index) has no normal and no area: it counts for
// no class (the multiplicity already leaves it out: its orientation with any eye is zero). A
// non-manifold edge (three or more proper triangles) is a silhouette when m != 0 and nothing
// otherwise: neither border nor crease. A triangle seen edge-on (the eye in its plane) adds
// nothing to m, so the edge between a visible face and an edge-on one is a silhouette. An edge
// may be silhouette and border at once (a lone triangle's edges); crease excludes both. Every
// decision is an exact sign: the classes do not change under vertex relabelling or face
// reversal (the bend angle and m depend on positions only), nor under an exact translation
// of soup and eye.
#include <cstdint>
#include <vector>

#include "core/soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

// Class bits of one edge; 0: none.
enum ViewEdgeClass : std::uint8_t {
  kSilhouetteEdge = 1,
  kBorderEdge = 2,
  kCreaseEdge = 4,
};

// The paper's two categories: profile = silhouette or border, inner = crease.
inline constexpr std::uint8_t kProfileEdges = kSilhouetteEdge | kBorderEdge;
inline constexpr std::uint8_t kInnerEdges = kCreaseEdge;

// The crease threshold's default: a bend above 30 degrees (cos 30 rounded once).
inline constexpr double kDefaultCreaseDegrees = 30.0;

struct ViewEdges {
  std::vector<std::uint8_t> classes;        // per edge of the table: ViewEdgeClass bits
  std::vector<std::int32_t> multiplicity;   // per edge: m with the eye as a point light
  std::vector<std::uint32_t> proper_faces;  // per edge: its proper triangles (copies counted)

  // How many edges have `bits` among their classes.
  [[nodiscard]] std::size_t count(std::uint8_t bits) const;
};

// The classes of every edge of `table` for an eye at `eye`, crease threshold theta given by
// its cosine (exact/normal_angle.h's angle_cosine; the bend must exceed theta strictly).
// Preconditions: `canonical` is a canonical soup and `table` its edge table, eye finite,
// crease_cosine in [-1, 1]; throws std::invalid_argument("view_edges: ...") otherwise.
[[nodiscard]] ViewEdges view_edges(const Soup& canonical, const EdgeTable& table, const Vec3& eye,
                                   double crease_cosine);

}  // namespace shadowcert
