#pragma once
// Smoothies (Chen & Tsai, "Improving Shadow Aliasing with Smoothies", §2.2-2.4, after Chan &
// Durand 2003; docs/smoothies.md): per silhouette edge of a light, a quad from the edge outwards,
// away from its occluders as the light sees them, whose alpha runs from 0 on the edge to 1 on the
// outer rim. A pure function over plain arrays: the caller (pipeline/scene_smoothies.h) picks the
// silhouette edges exactly; gpu/smoothie_map.h draws the result (core/smoothie_mesh.h).
//
// For an edge (u, v) and the light L = (l, w), the side plane holds u, v and the light; its normal
// n = (l - w u) x (v - u) makes (o - u) . n the value whose sign is D(u, v, o, L)
// (docs/definitions.md#orientation). The edge's occluders lie on the side `occluder_side`; the
// light-image direction p = -occluder_side * n / |n| is perpendicular to the edge and to the light's
// ray through it, and points away from them (Chan & Durand's smoothie direction).
//
//   world (Chen & Tsai, the default): the quad runs along the bisector B of the edge's faces,
//     B = -(sum of the unit in-face directions w_o from the edge towards each face's opposite
//     vertex o, perpendicular to the edge), i.e. the bisector of the outside of the dihedral
//     angle; on a convex silhouette edge it is the paper's bisector of the two face normals
//     (Eq. 1-5), and it always points away from faces on the occluders' side (B . p > 0). Width D
//     in world units at both ends.
//   light (Chan & Durand): the quad runs along p, perpendicular to the light's rays, and its width
//     at an end x is D |x - l| / reference_distance for a point light (a constant width in the
//     light's image: D at the reference distance), D for a directional light (an orthographic
//     image).
//
// Corners (Chen & Tsai Figure 9 and §2.4). Where exactly two smoothies meet at a vertex v (a
// silhouette chain passing through it), with other ends x_A and x_B:
//   concave in the light's image, c = (p_A . (x_B - v) / |x_B - v| + p_B . (x_A - v) / |x_A - v|) / 2
//     > kStraightCornerSine (each edge turns towards the other's smoothie, so the two overlap):
//     both widths at v are multiplied by (1 + p_A . p_B) / 2, the cosine squared of half the turn
//     (the paper's shrink: 1 on a straight chain, 1/2 at a right angle, 0 where the chain folds
//     back);
//   otherwise (convex or straight): the triangle (v, v'_A, v'_B) links the two rims, alpha 0, 1, 1,
//     so no gap opens between them (left out where v'_A and v'_B coincide).
// A vertex with one smoothie end (a chain's end) or three and more (chains crossing) is neither
// linked nor shrunk.
//
// Degenerate edges (defined behaviour, counted in SmoothieStats, never an exception):
//   - zero length (u and v at one position, or u == v): no smoothie;
//   - seen edge-on by the light (the light on the edge's line within kMinEdgeLightSine): no side
//     plane, no smoothie;
//   - world: a bisector of (near) zero length (faces on both sides of the side plane cancel), or
//     one that points within kMinBisectorOutwardCosine of the light's ray or inwards (B . p <=
//     that), takes the light-image direction p instead, so that no smoothie is drawn edge-on to
//     the light or into the occluders' shadow;
//   - a face whose opposite vertex lies on the edge's line adds nothing to the bisector.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/light.h"
#include "core/smoothie_mesh.h"
#include "core/soup.h"

namespace shadowcert {

// Tolerances of this approximate geometry (double arithmetic; the edges themselves are chosen
// exactly by the caller).
// |n| <= this * |l - w u| * |v - u|: the sine of the angle between the edge and the light's ray
// is at the level of the cross product's rounding (a few 1e-16) times a wide margin; the side
// plane's normal would be rounding noise.
inline constexpr double kMinEdgeLightSine = 1.0e-9;
// A unit in-face direction shorter than this fraction of |o - u| (before normalising): the face's
// opposite vertex is on the edge's line up to rounding, its direction is noise.
inline constexpr double kMinFaceWidthRatio = 1.0e-12;
// |B| below this (a sum of unit vectors): the faces cancel, there is no bisector.
inline constexpr double kMinBisectorLength = 1.0e-6;
// B . p / |B| at or below this (about 87 degrees from p): the smoothie would be seen nearly
// edge-on by the light (its image narrower than 5% of its width) or point inwards.
inline constexpr double kMinBisectorOutwardCosine = 0.05;
// |c| at or below this: a straight chain (no turn, up to rounding of unit vectors): linked, not
// shrunk.
inline constexpr double kStraightCornerSine = 1.0e-9;

enum class SmoothieSpace { world, light };

// "world" or "light" (the CLI's --smoothie-space values).
[[nodiscard]] std::string_view smoothie_space_name(SmoothieSpace space);
// The space of that name; nullopt for any other string.
[[nodiscard]] std::optional<SmoothieSpace> parse_smoothie_space(std::string_view name);

// The silhouette edges one light's smoothies grow from.
struct SmoothieEdges {
  std::vector<std::array<std::uint32_t, 2>> edges;  // (u, v): vertex indices
  // Per edge, +1 or -1: the sign of D(u, v, o, L) for the edge's occluders o (the side of the
  // side plane they lie on); the smoothie grows on the other side.
  std::vector<std::int8_t> occluder_side;
  // Edge e's faces are face_opposite[first_face[e] .. first_face[e + 1]): each face's vertex
  // opposite the edge, for the world-space bisector. first_face has edges + 1 entries.
  std::vector<std::uint32_t> first_face;
  std::vector<std::uint32_t> face_opposite;
};

struct SmoothieOptions {
  double width = 0.0;  // D: world units; light space: at reference_distance. Finite and > 0.
  SmoothieSpace space = SmoothieSpace::world;
  // Light space, point light: the distance from the light at which a smoothie is D wide (e.g.
  // to the centre of the scene's bounds). Finite and > 0 there; not read otherwise.
  double reference_distance = 0.0;
  bool link_corners = true;            // Figure 9
  bool shrink_concave_corners = true;  // §2.4
};

struct SmoothieStats {
  std::size_t edges = 0;               // silhouette edges given
  std::size_t smoothies = 0;           // quads built
  std::size_t zero_length_edges = 0;   // no smoothie
  std::size_t edge_on_edges = 0;       // no smoothie: the light on the edge's line
  std::size_t bisector_fallbacks = 0;  // world: direction p instead of the bisector
  std::size_t linked_corners = 0;      // linking triangles
  std::size_t shrunk_corners = 0;      // concave corners
};

struct Smoothies {
  SmoothieMesh mesh;  // per smoothie 4 vertices (u, v, v', u'; alpha 0, 0, 1, 1), 2 triangles,
                      // then one triangle per linked corner
  SmoothieStats stats;
};

// Throws std::invalid_argument("build_smoothies: ...") for a light that is not defined
// (core/light.h), a width or reference distance that is not finite and > 0 where it is read, an
// index out of range, an occluder side other than +-1, array sizes that do not match, or a
// non-finite coordinate of a vertex an edge or face uses.
[[nodiscard]] Smoothies build_smoothies(std::span<const Vec3> vertices, const SmoothieEdges& edges,
                                        const Light& light, const SmoothieOptions& options);

}  // namespace shadowcert
