#pragma once
// The uniform locations of the lit scene pass's interface, fixed by layout(location) in
// shadow_scene.vert.glsl and both fragment shaders that pair with it (shadow_scene.frag.glsl
// for the stencil methods, shadow_map_scene.frag.glsl for the shadow maps). One place, so the
// C++ side of each renderer cannot drift from the GLSL.

#include <epoxy/gl.h>

namespace shadowcert::gpu::shadow_scene_uniforms {

inline constexpr GLint kWorldToClip = 0;   // mat4, world -> clip
inline constexpr GLint kColour = 1;        // vec4, the light's colour share (rgb, a unused)
inline constexpr GLint kLight = 2;         // vec4 (l, w): w = 1 point, w = 0 directional
inline constexpr GLint kLambertWeight = 3; // float in [0, 1]: 0 flat, 1 Lambert

}  // namespace shadowcert::gpu::shadow_scene_uniforms
