#pragma once
// The GL layer for a host's context (docs/engine-integration.md#gl-layer): any volume
// method's stencil shadow volumes (cpu, cs, gs, ts, pertri, discrete, accurate, smooth,
// smooth-gpu) counted into the framebuffer the HOST has bound, with the host's
// view-projection matrix, over the depth the host has already drawn.
//
//   HostShadowVolumes shadows(ShadowMethod::cs, casters);       // uploads, compiles (once)
//   shadows.read_vertices_from(host_positions, canonical.canonical_id);  // optional: cs, gs, ts, pertri
//   // per frame, host framebuffer bound, its depth drawn:
//   shadows.build();                                           // GPU builds, queued
//   shadows.draw_stencil(world_to_clip, 0);                    // stencil-only entry: counts
//   ... the host lights where the stencil is 0 ...
//   // or the full entry: counts, then shadowcert's Lambert light added where the count is 0
//   shadows.draw_lit(world_to_clip, 0, receivers, {0.85f, 0.85f, 0.85f});
//
// State contract: every entry point captures the state gpu/gl_state_snapshot.h lists and puts
// it back before it returns (tests/gpu/host_shadow_volumes_test.cpp checks it); it changes the
// bound draw framebuffer's stencil (and, in draw_lit, its colour) and nothing else. It needs
// (and never changes) the host's draw framebuffer with a stencil buffer of 8 bits (counts are
// modulo 256) and its depth drawn by a vertex stage that computes
//   invariant gl_Position;  precise vec4 clip = world_to_clip * vec4(position, 1.0);
// with the same world_to_clip (so a cap on its own triangle gets the host's depth exactly),
// and the host's viewport and scissor (read by GL, not by us). No entry point waits for the
// GPU, except check_capacity(), which is for asking.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/gl_object.h"
#include "gpu/host_vertex_buffer.h"
#include "gpu/shadow_method.h"
#include "gpu/sign_mode.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

struct ShadowMethodScene;  // gpu/shadow_method_renderer.h
class ShadowVolumeSet;     // gpu/shadow_volume_set.h
class ShadowSceneProgram;  // gpu/stencil_passes.h

// The host's receivers as the full entry (draw_lit) lights them: per vertex a position (3 or
// 4 components), a normal (3) and an albedo (3), each from a host buffer; drawn as
// GL_TRIANGLES, indexed when index_buffer is not 0 (count indices of index_type at
// index_offset), else count vertices from first. Normals are turned towards the viewer, so a
// soup's orientation does not matter.
struct HostReceivers {
  HostVertexBuffer position;
  HostVertexBuffer normal;
  HostVertexBuffer albedo;
  GLuint index_buffer = 0;
  GLenum index_type = GL_UNSIGNED_INT;  // GL_UNSIGNED_BYTE, GL_UNSIGNED_SHORT or GL_UNSIGNED_INT
  GLintptr index_offset = 0;
  GLint first = 0;
  GLsizei count = 0;
};

// The receivers of shadowcert's own interleaved mesh (position 4, normal 3, albedo 3 floats
// per vertex, drawn unindexed) as a host's: what the viewer, tests and benchmarks hand draw_lit.
[[nodiscard]] HostReceivers host_receivers(const ShadedSoupMesh& mesh);

struct HostShadowOptions {
  StencilMethod stencil = StencilMethod::zfail;  // every light without its own
  // Empty, or one stencil method per light (pipeline/stencil_choice.h's proofs for z-pass).
  std::vector<StencilMethod> light_stencil;
  SignMode sign = SignMode::exact;  // cs, gs, ts, pertri
};

class HostShadowVolumes {
 public:
  // `casters`: the lights and what the method reads (gpu/shadow_method_renderer.h's
  // ShadowMethodScene; its receivers are not read: the host draws those). cpu_volumes must
  // outlive this object. Needs the host's context current; throws std::invalid_argument
  // ("HostShadowVolumes: ...") for a shadow-map method or missing inputs, GlError with the
  // driver's message. Restores the state it changes (the contract above).
  HostShadowVolumes(ShadowMethod method, const ShadowMethodScene& casters, const HostShadowOptions& options = {});
  ~HostShadowVolumes();
  HostShadowVolumes(HostShadowVolumes&&) noexcept;
  HostShadowVolumes& operator=(HostShadowVolumes&&) noexcept;

  [[nodiscard]] ShadowMethod method() const { return method_; }
  [[nodiscard]] std::size_t light_count() const;

  // cs, gs, ts, pertri: from now on each build() reads the casters' positions from the host's
  // buffer (positions may move between frames; the topology is the construction's):
  // `vertices` holds the host's vertices (3 components, GL_FLOAT or GL_DOUBLE, offset and
  // stride multiples of 4 resp. 8 bytes), and canonical_id[i] is host vertex i's canonical
  // index (scene/canonical_soup.h's CanonicalSoup::canonical_id of the host's soup). Throws
  // std::invalid_argument("HostShadowVolumes::read_vertices_from: ...") for another method, a
  // bad layout, or a canonical_id that misses a canonical vertex or exceeds their count.
  void read_vertices_from(const HostVertexBuffer& vertices, std::span<const std::uint32_t> canonical_id);

  // cs, gs, ts, pertri: light k moves (the next build() follows it). Throws as
  // ShadowVolumeSet::set_light (gpu/shadow_volume_set.h): std::invalid_argument for the
  // methods given a volume per light, std::out_of_range.
  void set_light(std::size_t k, const Light& light);

  // Queues every light's GPU build (and the gather from the host's buffer first); nothing
  // for the given volumes. Never waits.
  void build();

  // The stencil-only entry: clears the bound framebuffer's stencil to 0 and counts light
  // `light`'s volume into it (z-fail or z-pass as chosen), colour and depth untouched. The
  // host then lights where the stencil is 0. Throws std::out_of_range for a light out of range.
  void draw_stencil(const glm::mat4& world_to_clip, std::size_t light) const;

  // The full entry: draw_stencil, then `receivers` lit by light `light` with `light_colour`
  // (Lambert, two-sided) where the count is 0 and the depth equals the host's, added to the
  // colour (GL_ONE, GL_ONE); the stencil ends at 1 where a pixel was lit.
  void draw_lit(const glm::mat4& world_to_clip, std::size_t light, const HostReceivers& receivers,
                const std::array<float, 3>& light_colour) const;

  // Waits for the GPU: throws VolumeCapacityError when a light's last build overflowed.
  void check_capacity() const;

 private:
  void count(const glm::mat4& world_to_clip, std::size_t light) const;

  ShadowMethod method_;
  StencilMethod stencil_ = StencilMethod::zfail;
  std::unique_ptr<ShadowVolumeSet> volumes_;
  std::unique_ptr<ShadowSceneProgram> program_;
  VertexArray receivers_;  // set from HostReceivers at each draw_lit
  // read_vertices_from: the gather program, the host index per canonical vertex, the source.
  Program gather_;
  Buffer host_index_;
  std::optional<HostVertexBuffer> host_vertices_;
};

}  // namespace shadowcert::gpu
