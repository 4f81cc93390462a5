#pragma once
// The shadow-volume library without GL (docs/engine-integration.md#volume-library-no-gl), in
// the spirit of Doom 3 BFG's shadow-volume job: the caller's soup (its arrays) and a light in,
// the robust volume out, written into the caller's buffers as homogeneous float vertices and
// uint32 triangle indices, with per-volume flags (z-pass proven or z-fail needed, bounds).
//
//   VolumeWorkspace ws;                                  // once per thread (or per soup)
//   ws.set_soup(positions, indices);                     // sizing call: weld, edge table, reserve
//   for each light, each frame:
//     const VolumeSizes need = ws.build(light);          // the hot path: the exact volume
//     grow(vertex_buffer, need.position_floats()); grow(index_buffer, need.index_count());
//     const VolumeInfo info = ws.write(vertex_buffer, index_buffer, &view);
//   (or ws.generate(light, vertex_buffer, index_buffer, &view): build + write in one call)
//
// The volume is the one `render --method cpu` draws, from the very same code
// (exact/cpu_volume.h's rounded_cpu_volume): the exact chain of the soup welded and ordered
// (scene/canonical_soup.h), every coordinate and the light rounded once to float as a GL upload
// rounds them; side quads repeated |m| times by their exact multiplicity m, front caps, and
// for a point light the back caps at infinity. It is closed (docs/definitions.md#closure) and
// its winding number is the occluder count (docs/definitions.md#counts) for any soup.
//
// Output layout (exact/chain_mesh.h's vertex ids): vertex i in [0, n) is the soup's welded
// vertex i (n welded vertices, in lexicographic order of position; input_vertex_ids() maps the
// caller's vertices to them) with w = 1; a point light's vertex n + i is vertex i's point at
// infinity (x_i - l, 0), a directional light's vertex n the one point at infinity (-l, 0); from
// 2n on, the extra far vertices of split wide far edges (chain_mesh.h). Vertices no triangle
// uses (a soup vertex that casts nothing) are written too, so ids stay fixed. Triangles are
// oriented outwards (right-hand rule); draw them with GL_TRIANGLES, any stencil convention
// that counts front faces +1 and back faces -1 (docs/gpu.md).
//
// Threads: no shared mutable state. One workspace is used by one thread at a time; workspaces
// on different threads (two soups, or one soup set on each) run concurrently. The work inside
// build() runs in parallel on TBB's threads.
//
// Allocation: set_soup() allocates (its copy of the soup, the edge table, and every array of
// the build sized for the largest volume without split far edges: caps of every triangle, |m|
// side quads of every edge entry). After it, build() and write() allocate no array
// proportional to the soup: every step refills the workspace's arrays within their capacity.
// What may still allocate, small: per-chunk counters (one per 32768 triangles or edges), TBB's
// task objects, CGAL's exact arithmetic on the rare triangles whose sign the floating-point
// filter cannot certify (near-degenerate configurations), and, only when the light lies close
// to the line of an edge and between its ends, the split far edges' table and vertices. The
// z-pass proof (VolumeView::tip) allocates (it builds an occluder-count tree). Measured by
// tests/volume/volume_workspace_test.cpp (bytes allocated by a build after set_soup).
//
// Errors: misuse throws std::invalid_argument("VolumeWorkspace::<function>: ...").
#include <cstdint>
#include <memory>
#include <span>

#include "core/light.h"
#include "volume/volume_info.h"
#include "volume/volume_method.h"
#include "volume/volume_sizes.h"
#include "volume/volume_view.h"

namespace shadowcert {

class VolumeWorkspace {
 public:
  // Empty: no soup. Movable (a moved-from workspace may only be assigned to or destroyed), not
  // copyable (it holds the arrays of a soup's builds).
  VolumeWorkspace();
  ~VolumeWorkspace();
  VolumeWorkspace(VolumeWorkspace&&) noexcept;
  VolumeWorkspace& operator=(VolumeWorkspace&&) noexcept;
  VolumeWorkspace(const VolumeWorkspace&) = delete;
  VolumeWorkspace& operator=(const VolumeWorkspace&) = delete;

  // The soup every later build() is of, copied (the caller's arrays may go away after):
  //   positions: 3 * n values x0 y0 z0 x1 y1 z1 ..., float or double, every one finite (and,
  //              for double, within float's range: the volume is of the float-rounded soup);
  //   indices:   3 * t values, triangle k = (indices[3k], indices[3k + 1], indices[3k + 2]),
  //              each < n. Any soup: open, non-manifold, repeated or degenerate triangles.
  // Welds it, builds its edge table and sizes the build's arrays (above). Float and double
  // positions with the same values give the same volume. Throws std::invalid_argument
  // ("VolumeWorkspace::set_soup: ...") naming the first bad value: a length not a multiple of
  // 3, a non-finite or float-overflowing coordinate, an index out of range, 2^31 vertices or
  // more. On a throw the workspace holds no soup.
  void set_soup(std::span<const float> positions, std::span<const std::uint32_t> indices);
  void set_soup(std::span<const double> positions, std::span<const std::uint32_t> indices);

  // Builds `light`'s volume by `method` into the workspace (the work: exact multiplicities,
  // the chain, its homogeneous mesh) and returns its size: the query of how much write()
  // needs. `light`: position (x, y, z, 1) of a point light or direction (x, y, z, 0) towards a
  // directional one (core/light.h), finite, and finite once rounded to float; a directional
  // light's direction is not (0, 0, 0). Throws std::invalid_argument("VolumeWorkspace::build:
  // ...") on such a light or with no soup set.
  VolumeSizes build(const Light& light, VolumeMethod method = VolumeMethod::cpu);

  // The last build's size (all zero before any).
  [[nodiscard]] VolumeSizes sizes() const;

  // Writes the last build's volume into the caller's buffers:
  //   positions: at least sizes().position_floats() floats: vertex v is positions[4v .. 4v + 3],
  //              (x, y, z, w), w = 1 (finite) or 0 (at infinity), as GL's vec4 attribute;
  //   indices:   at least sizes().index_count() uint32: triangle k is indices[3k .. 3k + 2].
  // Entries past those are left untouched. `view` (optional) adds the depth bounds and, with a
  // tip, the z-pass proof (VolumeInfo). Throws std::invalid_argument("VolumeWorkspace::write:
  // ...") when a span is too small (naming both lengths) or nothing was built.
  [[nodiscard]] VolumeInfo write(std::span<float> positions, std::span<std::uint32_t> indices,
                                 const VolumeView* view = nullptr) const;

  // build() then write() in one call; the errors name VolumeWorkspace::generate. When a span is
  // too small the volume is built all the same: sizes() tells how much to grow them, and
  // write() then writes it without building again.
  VolumeInfo generate(const Light& light, std::span<float> positions, std::span<std::uint32_t> indices,
                      const VolumeView* view = nullptr, VolumeMethod method = VolumeMethod::cpu);

  // For each of the caller's vertices (set_soup's order), its vertex id in the volume: where a
  // host that keeps its own vertex buffer finds each vertex (equal positions share one id).
  // Empty before set_soup.
  [[nodiscard]] std::span<const std::uint32_t> input_vertex_ids() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowcert
