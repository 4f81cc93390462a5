#pragma once
// The smoothies of a scene's casters, one mesh per light (docs/smoothies.md): the silhouette
// edges chosen exactly here, their quads built by contour/smoothie.h, drawn by the `smoothie`
// method (gpu/shadow_method_renderer.h, gpu/smoothie_map.h).
//
// Silhouette edges (docs/definitions.md#counts, docs/smoothies.md): the edges of the casters' canonical
// soup with exact multiplicity m != 0 for the light, taken on the input as GL receives it (every
// coordinate and the light rounded to float, core/float_rounding.h; the same indices, as cpu's
// chain). On an edge of exactly two triangles that run it in opposite directions (an oriented
// manifold edge) this is the face-pair test, one face lit and the other not, with a face that
// has the light in its plane casting nothing; on any other edge (soups: open, non-manifold,
// misoriented) it is the chain's own rule, so no edge is dropped. The occluders' side is the
// side of the majority, -sign(m). The bisector's faces are the edge's triangles on that side,
// and on a manifold edge also a face with the light in its plane.
//
//   SceneSmoothies s = scene_smoothies(inputs.canonical.soup, inputs.table, lights, bounds, {});
#include <span>
#include <vector>

#include "contour/smoothie.h"
#include "core/light.h"
#include "core/smoothie_mesh.h"
#include "core/soup.h"
#include "gpu/shadow_map_renderer.h"
#include "scene/edge_table.h"

namespace shadowcert {

// Without --smoothie-width: this fraction of the diagonal of the scene's bounding box (the
// receivers', what the light map is fitted to). 0.02 gives default.json (diagonal about 17) a
// smoothie width of about 0.34, a third of its casters' size.
inline constexpr double kDefaultSmoothieWidthFraction = 0.02;

struct SceneSmoothieOptions {
  double width = 0.0;  // D in world units (> 0, finite); 0: kDefaultSmoothieWidthFraction of the diagonal
  SmoothieSpace space = SmoothieSpace::world;
  bool link_corners = true;
  bool shrink_concave_corners = true;
};

struct SceneSmoothies {
  std::vector<SmoothieMesh> per_light;  // in the lights' order
  std::vector<SmoothieStats> stats;     // likewise
  double width = 0.0;                   // the D used
  SmoothieSpace space = SmoothieSpace::world;
};

// The silhouette edges of `light` on `soup` (with `table` = build_edge_table of its canonical
// form: the same triangles and indices), as described above, exactly for the values given
// (scene_smoothies gives the float-rounded ones). Throws std::invalid_argument from the exact
// multiplicities (an undefined light, a table that does not fit the soup).
[[nodiscard]] SmoothieEdges smoothie_edges(const Soup& soup, const EdgeTable& table, const Light& light);

// Every light's smoothies. `bounds`: the scene's (every receiver, gpu::soup_bounds), for the
// default width and for light space, whose reference distance is each point light's distance to
// the bounds' centre (where the light map is aimed), or half the bounds' diagonal for a light at
// that centre (it has a cube map, aimed nowhere). Throws std::invalid_argument
// ("scene_smoothies: ...") for a width that is negative or not finite, and what smoothie_edges
// and build_smoothies throw.
[[nodiscard]] SceneSmoothies scene_smoothies(const Soup& canonical, const EdgeTable& table,
                                             std::span<const Light> lights, const gpu::SceneBounds& bounds,
                                             const SceneSmoothieOptions& options = {});

}  // namespace shadowcert
