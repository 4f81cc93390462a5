#pragma once
// Whether z-pass stencil counting is PROVEN right for one light and one camera, decided
// exactly (docs/gpu.md#proven-z-pass).
//
// Z-pass counts the chain's faces between the eye and the visible point P; that is n(P) only
// when the count where counting starts is 0. Engines guess this with bounding boxes (Doom 3's
// automatic z-fail); here it is proven. The volume pass runs with GL_DEPTH_CLAMP on (no near
// clipping), so counting starts at the eye; the region near it is the frustum's TIP: the union
// of the tetrahedra (apex, c0, c1, c2) and (apex, c0, c2, c3), apex the eye and c0..c3 the near
// rectangle's corners in cyclic order. z-pass is proven when
//   (a) no face of the exact chain of docs/definitions.md#counts meets the closed tip: no front
//       cap (a casting triangle, s != 0) and no side face {l + t (x - l) : x on [u, v], t >= 1}
//       (point light) or {x - t l : x on [u, v], t >= 0} (directional) of an edge with exact
//       multiplicity m != 0 (back caps lie at infinity and meet no finite set); a touch, a
//       shared point or any degenerate contact counts as meeting;
//   (b) n = 0 in the tip: the exact occluder count (exact/count_certificate.h's
//       OccluderCounter) of the apex is 0.
// By (a) the chain's winding number is constant on the (connected) tip, and it equals n
// wherever n is defined (docs/definitions.md#counts, the counting identity); so by (b) n = 0
// wherever it is defined in the tip, no V(t) meets the tip's interior, and the winding number
// of ANY chain sum c(t) dV(t) (a float method's, docs/definitions.md#float-methods) is 0 there
// too: z-pass's count from any point of the tip to P is then that chain's winding at P, which
// is what z-fail counts. When n is undefined at the apex (its segment to the light touches a
// caster) and (a) holds, the tips' centroids are counted instead (each checked exactly to lie
// in the tip).
//
// Every decision is exact on the input doubles: orientation signs (exact/face_crossing.h) for
// the tip's edges against side faces and for quick rejections; CGAL's do_intersect with exact
// predicates for caps and the segment uv against the tetrahedra, and with exact constructions
// for the side faces' rays (direction u - l of a point light is not a double). No tolerance:
// a caller that must absorb rounding elsewhere (GL's float transform) passes a larger tip.
#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/light.h"
#include "core/soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

enum class ZPassVerdict : std::uint8_t {
  proven,            // (a) and (b): z-pass counts what z-fail counts
  camera_in_volume,  // n(apex) > 0 (or, with (a), n > 0 at a probe of the tip)
  face_meets_tip,    // n(apex) = 0 or undefined, and a face of the exact chain meets the closed tip
  count_undefined,   // (a) holds, but n is undefined at the apex and at every probe of the tip
};

// "proven", "camera_in_volume", "face_meets_tip", "count_undefined" (the JSON's reasons).
[[nodiscard]] std::string_view zpass_verdict_name(ZPassVerdict verdict);

enum class ChainFace : std::uint8_t { none, front_cap, side };

struct ZPassProof {
  ZPassVerdict verdict = ZPassVerdict::count_undefined;
  // n at the apex: nullopt when undefined there (its segment to the light touches a caster).
  std::optional<std::uint32_t> apex_count;
  // face_meets_tip: the first face found meeting the tip: a front cap (`face` is the soup's
  // triangle index) or a side (`face` is the edge's index in the table, `edge` its vertex ids
  // (u, v), `multiplicity` its m).
  ChainFace face_kind = ChainFace::none;
  std::uint32_t face = 0;
  std::array<std::uint32_t, 2> edge{};
  std::int32_t multiplicity = 0;

  [[nodiscard]] bool proven() const { return verdict == ZPassVerdict::proven; }
};

// `soup` and `table`: scene/canonical_soup.h's soup (or it rounded to float, exact/cpu_volume.h:
// ids and topology unchanged) and build_edge_table of it; `light`: core/light.h's
// Light::defined(); `apex` (the eye) and `corners` (the near rectangle, cyclic) span two
// proper tetrahedra of one orientation: orient(apex, c0, c1, c2) = orient(apex, c0, c2, c3) != 0.
// Throws std::invalid_argument("prove_zpass: ...") on a bad light, a table that does not fit,
// a non-finite coordinate or such a degenerate tip.
[[nodiscard]] ZPassProof prove_zpass(const Soup& soup, const EdgeTable& table, const Light& light, const Vec3& apex,
                                     const std::array<Vec3, 4>& corners);

}  // namespace shadowcert
