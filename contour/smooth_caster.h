#pragma once
// A caster drawn with smooth silhouettes (Mattausch et al. 2012; docs/smooth-silhouettes.md):
// an oriented 2-manifold triangle mesh, borders allowed, with a unit normal at every corner.
// Whether a soup qualifies is stated, never guessed: smooth_caster() returns either the
// caster or the report that names the first offending edges and vertices, and a caster that
// does not qualify is drawn by the robust chain instead (docs/smooth-silhouettes.md, "Who
// qualifies").
//
// Built once per mesh, independent of the light. Connectivity comes from OpenMesh (inside
// contour/*.cpp only), on the exactly welded soup (scene/welded_soup.h: equal doubles are one
// vertex, nothing else is).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/soup.h"

namespace shadowcert {

// The dihedral angle above which an edge is a crease when normals are computed: each side
// keeps its own corner normals there. 60 degrees keeps every uv sphere from 6 slices up smooth
// (its faces meet at 360 / slices degrees) and creases a box (90).
inline constexpr double kDefaultCreaseAngleDegrees = 60.0;

// Where the corner normals come from.
enum class CornerNormalSource {
  file,      // the soup's per-vertex normals, normalised (each corner takes its input vertex's)
  computed,  // OpenMesh's halfedge normals: the sum of the unit face normals around the corner's
             // vertex, up to the nearest crease or border on each side, normalised; every corner
             // of one such wedge gets the same bits
};

struct SmoothCasterOptions {
  double crease_angle_degrees = kDefaultCreaseAngleDegrees;  // in [0, 180]; computed normals only
  bool use_file_normals = true;  // take the soup's normals when it has them
};

// Why a soup is not an oriented 2-manifold, the first kMaxReported items of each kind, as
// indices of the welded soup (vertices) and of the input (triangles).
struct CasterQualification {
  static constexpr std::size_t kMaxReported = 8;
  std::vector<std::uint32_t> degenerate_triangles;            // repeated welded index or zero area
  std::vector<std::array<std::uint32_t, 2>> non_manifold_edges;  // more than two triangles
  std::vector<std::array<std::uint32_t, 2>> misoriented_edges;   // two triangles run it the same way
  std::vector<std::uint32_t> non_manifold_vertices;           // its triangles are not one fan
  // Counts of every offender (the vectors above hold the first few).
  std::size_t degenerate_count = 0, non_manifold_edge_count = 0, misoriented_edge_count = 0,
              non_manifold_vertex_count = 0;

  [[nodiscard]] bool qualifies() const {
    return degenerate_count + non_manifold_edge_count + misoriented_edge_count + non_manifold_vertex_count == 0;
  }
  // One line: "qualifies", or e.g. "not an oriented 2-manifold: 2 non-manifold edges ((3, 7),
  // (7, 9)); 1 non-manifold vertex (12)".
  [[nodiscard]] std::string summary() const;
};

inline constexpr std::uint32_t kBorder = 0xFFFFFFFFu;  // no triangle across an edge

struct SmoothCaster {
  std::vector<Vec3> vertices;      // welded positions (unreferenced ones kept)
  std::vector<Triangle> triangles;  // welded indices, in the input's order and orientation
  // normals[t][k]: the unit normal at corner k of triangle t (k = 0, 1, 2 as in triangles[t]).
  std::vector<std::array<Vec3, 3>> normals;
  // The wedges: corners of one vertex with one normal (bit for bit). wedge[t][k] is corner k's;
  // wedge_vertex[w] and wedge_normal[w] are the wedge's. A light's corner values are computed
  // once per wedge (contour/detail/lit_boundary.h), a third of the corners on a smooth mesh.
  std::vector<std::array<std::uint32_t, 3>> wedge;
  std::vector<std::uint32_t> wedge_vertex;
  std::vector<Vec3> wedge_normal;
  // across[t][k]: the triangle across edge k = (corner k, corner k + 1 mod 3) of t, or kBorder.
  std::vector<std::array<std::uint32_t, 3>> across;
  // crease[t][k]: edge k of t is a crease. Computed normals: the dihedral angle there exceeds the
  // crease angle (OpenMesh's feature edge). File normals: the two triangles' corner normals
  // differ at an end. False at a border.
  std::vector<std::array<bool, 3>> crease;
  // Every crease once, as (t, k) of its side with the lower triangle index: what the silhouettes
  // walk to find crease pieces without visiting every edge.
  std::vector<std::array<std::uint32_t, 2>> crease_edges;
  CornerNormalSource normal_source = CornerNormalSource::computed;
};

struct SmoothCasterResult {
  std::optional<SmoothCaster> caster;  // set iff qualification.qualifies()
  CasterQualification qualification;
};

// Preconditions (std::invalid_argument("smooth_caster: ...")): indices in range, finite
// vertices, crease angle in [0, 180]. A soup without triangles qualifies (an empty caster).
[[nodiscard]] SmoothCasterResult smooth_caster(const Soup& soup, const SmoothCasterOptions& options = {});

}  // namespace shadowcert
