#pragma once
// The passes of the stencil shadow method (gpu/stencil_shadow_renderer.h says why each state is
// what it is), shared by the offscreen renderer (StencilShadowRenderer) and the host layer
// (gpu/host_shadow_volumes.h), so that a volume counted into shadowcert's own target and into
// a host's framebuffer is the same draw with the same state:
//
//   ShadowSceneProgram program;                     // shadow_scene.{vert,frag}.glsl
//   program.set_world_to_clip(world_to_clip);
//   glUseProgram(program.name());
//   begin_volume_pass();                            // stencil cleared, counts only
//   count_volume(light_volume, StencilMethod::zfail);
//   end_volume_pass();
//   begin_lit_pass(program, light, colour);         // where the count is 0, depth GL_EQUAL
//   ... draw the receivers ...
//   end_lit_pass(program);
//
// These functions set GL state and leave it set (the offscreen renderer owns its context); the
// host layer wraps them in gpu/gl_state_snapshot.h's ScopedGlState.
#include <array>

#include <glm/glm.hpp>

#include "core/light.h"
#include "gpu/gl_object.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

// shadow_scene.{vert,frag}.glsl: one program, one matrix, one expression for every pass (the
// depth pass, the volumes and the lit pass rasterise to bit-identical depths).
class ShadowSceneProgram {
 public:
  ShadowSceneProgram();  // compiles and links; throws GlError with the driver's log

  [[nodiscard]] GLuint name() const { return program_.name(); }
  // world_to_clip: column-major, clip = world_to_clip * (x, y, z, w) (glm's convention).
  void set_world_to_clip(const glm::mat4& world_to_clip) const;
  // The ambient pass: albedo * rgb, alpha 1 (covered pixels).
  void set_ambient(const std::array<float, 3>& rgb) const;
  // The lit pass: albedo * rgb * Lambert term towards `light`, alpha 0, added by blending.
  void set_lit(const Light& light, const std::array<float, 3>& rgb) const;

 private:
  Program program_;
};

// The volume pass's state: the stencil cleared to 0 (through stencil mask 0xFF and the clear
// value 0), the stencil test on with GL_ALWAYS, colour and depth writes off, depth GL_LESS (a
// cap at the visible point's own depth fails: "behind" it) and GL_DEPTH_CLAMP on (w = 0 caps
// reach depth 1 exactly, and with a finite far plane nothing beyond it is clipped).
void begin_volume_pass();
// Counts `volume` into the stencil with `method`'s operations (z-fail: back +1 / front -1
// where the depth test fails; z-pass: front +1 / back -1 where it passes), in the bound
// program (attribute 0 the vec4 position, the world_to_clip uniform set). Leaves the stencil
// operations of `method` set and no vertex array or indirect buffer bound.
void count_volume(const LightVolume& volume, StencilMethod method);
// GL_DEPTH_CLAMP off again.
void end_volume_pass();

// The lit pass's state for `light` with colour `rgb` in `program`: stencil GL_EQUAL 0, each
// pixel lit once (GL_INCR on pass, so a second receiver copy at the same depth fails), colour
// writes on, depth GL_EQUAL, additive blending (GL_FUNC_ADD, GL_ONE, GL_ONE).
void begin_lit_pass(const ShadowSceneProgram& program, const Light& light, const std::array<float, 3>& rgb);
// Blending off; the program's Lambert weight back to 0 (the ambient pass).
void end_lit_pass(const ShadowSceneProgram& program);

}  // namespace shadowcert::gpu
