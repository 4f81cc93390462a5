#version 450 core
// Scene pass of the shadow map (with shadow_scene.vert.glsl, so the ambient pass and the lit
// pass rasterise to identical depths and GL_EQUAL holds).
// Ambient pass (lambert_weight = 0): albedo * colour, alpha 1 marks covered pixels.
// Lit pass (lambert_weight = 1): the visible point's light-space depth, less depth_bias, is
// compared with the map (GL_COMPARE_REF_TO_TEXTURE, GL_LEQUAL: 1 = lit) by the filter of
// shadow_filter.glsl (hard: one comparison; pcf, pcss, smoothie: an amount in [0, 1]);
// fragments that get no light, and those of a side facing away from the light, are discarded so
// that neither their colour nor their stencil mark is written, the others add
// albedo * colour * max(n . d, 0) * amount (two-sided, as shadow_scene.frag.glsl).
// Light-image pass (light_image_pass = 1, into an R32F target, gpu/light_image_target.h): the
// amount itself, 0 on a side facing away from the light; nothing else is discarded.
// A point light drawn with a cube map (cube_face >= 0, gpu/shadow_map_renderer.h's light_views)
// runs the lit and light-image passes once per face with that face's map and matrices: each
// pass keeps only the fragments whose direction from the light falls in its face
// (cube_face.glsl) and discards the others, which another face's pass lights.
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec3 surface_albedo;
layout(location = 1) uniform vec4 colour;
layout(location = 2) uniform vec4 light;       // (l, w): w = 1 point, w = 0 directional
layout(location = 3) uniform float lambert_weight;
layout(location = 4) uniform mat4 light_to_clip;
layout(location = 5) uniform float depth_bias;
layout(location = 12) uniform int light_image_pass;
layout(location = 13) uniform int cube_face;  // 0..5: this pass's face of a cube map; -1: one map
layout(binding = 0) uniform sampler2DShadow shadow_map;
layout(location = 0) out vec4 fragment;

#include "shadow_filter.glsl"
#include "cube_face.glsl"

void main() {
  // The point in the light's window and its screen derivatives, taken first, in uniform control
  // flow (derivatives are undefined in a branch some fragments of a quad skip): what the filters'
  // receiver-plane depth bias needs (shadow_filter.glsl).
  vec4 clip = light_to_clip * vec4(world_position, 1.0);
  vec3 window = (clip.xyz / clip.w) * 0.5 + 0.5;  // glDepthRange(0, 1), the default
  vec2 gradient = receiver_depth_gradient(dFdx(window), dFdy(window));
  if (lambert_weight == 0.0) {
    fragment = vec4(surface_albedo * colour.rgb, 1.0);
    return;
  }
  if (cube_face >= 0 && cube_face_of(world_position - light.xyz) != cube_face) discard;
  float lambert = 0.0;
  float n_length = length(world_normal);
  if (n_length > 0.0) {
    vec3 n = world_normal / n_length;
    if (!gl_FrontFacing) n = -n;
    vec3 to_light = light.w == 0.0 ? light.xyz : light.xyz - world_position;
    float d_length = length(to_light);
    if (d_length > 0.0) lambert = dot(n, to_light / d_length);
    // The side of a surface turned away from the light is in its own shadow. The map cannot
    // say so (that side is as near the light as the lit one), the volume methods do (the
    // point is behind its own triangle's cap), and the lit masks must mean the same thing.
    if (lambert <= 0.0) {
      if (light_image_pass == 1) {
        fragment = vec4(0.0);
        return;
      }
      discard;
    }
  }
  float amount = 1.0;
  // The frustum is fitted to the scene's bounds, so every receiver point is inside it; a
  // point outside (w <= 0 or beyond [-1, 1]) has nothing in the map to hide it: lit.
  // A cube face holds every fragment kept above sideways; one nearer than the face's near plane
  // (none when the near plane is the nearest receiver's, light_views) compares at depth 0, where
  // the depth pass clamped any caster that near (GL_DEPTH_CLAMP): lit unless a caster is nearer.
  if (clip.w > 0.0) {
    vec3 ndc = clip.xyz / clip.w;
    // textureLod inside: no derivatives needed (one level) in this non-uniform branch.
    if (cube_face >= 0) {
      amount = filtered_light(vec3(window.xy, clamp(window.z, 0.0, 1.0)), gradient, world_position);
    } else if (all(lessThanEqual(abs(ndc), vec3(1.0)))) {
      amount = filtered_light(window, gradient, world_position);
    }
  }
  if (light_image_pass == 1) {
    fragment = vec4(amount, 0.0, 0.0, 0.0);
    return;
  }
  if (amount <= 0.0) discard;
  fragment = vec4(surface_albedo * colour.rgb * lambert * lambert_weight * amount, 0.0);
}
