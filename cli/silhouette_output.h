#pragma once
// How each mesh cast under a smooth-silhouette method (pipeline/silhouette_volumes.h), as
// `render` and `diff` report it: one line per mesh, and the JSON's "casters" array
// (docs/cli.md, docs/smooth-silhouettes.md).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "pipeline/silhouette_volumes.h"

namespace shadowcert::cli {

// --epsilon E and --crease-angle DEG of render, diff and certify, read into `options`
// (near_plane is the caller's).
void add_silhouette_options(CLI::App& command, SilhouetteOptions& options);

// [{"mesh": name, "triangles": n, "cast_by": "discrete"|"accurate"|"smooth"|"robust chain"|"nothing"
//   (the command's method or the mesh's own "silhouette"; "nothing": "casts": false),
//   "epsilon": the contour error when cast by smooth, else null,
//   "qualification": "qualifies", the report naming the offenders, or why the mesh was not asked
//   ("the scene asks for the chain", "the scene says it casts nothing"), "loops": first light's}, ...]
[[nodiscard]] nlohmann::json silhouette_casters_json(const SilhouetteVolumes& volumes);

// "  smooth: MESH (N triangles) cast by smooth (epsilon 0.01), 1 loop", "... cast by discrete, 2
// loops", "... cast by the robust chain: not an oriented 2-manifold: ..." or "... casts nothing:
// the scene says it casts nothing", per mesh, on stdout.
void print_silhouette_casters(const SilhouetteVolumes& volumes);

}  // namespace shadowcert::cli
