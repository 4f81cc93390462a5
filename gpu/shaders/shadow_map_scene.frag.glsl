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
// A point light drawn with a cube map (cube_map = 1, gpu/shadow_map_renderer.h's light_views):
// one lit pass as for one map, each fragment reading the layer, matrix and frustum of the face
// its direction from the light falls in (cube_face.glsl).
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec3 surface_albedo;
layout(location = 1) uniform vec4 colour;
layout(location = 2) uniform vec4 light;       // (l, w): w = 1 point, w = 0 directional
layout(location = 3) uniform float lambert_weight;
layout(location = 4) uniform mat4 light_to_clip;
layout(location = 5) uniform float depth_bias;
layout(location = 12) uniform int light_image_pass;
layout(location = 13) uniform int cube_map;    // 1: the light has a cube map (below); 0: one map
layout(location = 14) uniform int cube_faces;  // bit f set: face f was drawn (light_views leaves out empty ones)
layout(location = 16) uniform mat4 cube_light_to_clip[6];  // per face, world to its clip space
layout(location = 22) uniform mat4 cube_light_view[6];     // per face, world to its view
layout(location = 28) uniform vec4 cube_light_frustum[6];  // per face, as light_frustum
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
  vec3 dpx = dFdx(world_position), dpy = dFdy(world_position);  // a cube face's gradient
  view_of_light = light_view;
  frustum_of_light = light_frustum;
  if (lambert_weight == 0.0) {
    fragment = vec4(surface_albedo * colour.rgb, 1.0);
    return;
  }
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
  // A cube face holds every direction of its face sideways; a point nearer than the face's near
  // plane (none when the near plane is the nearest receiver's, light_views) compares at depth 0,
  // where the depth pass clamped any caster that near (GL_DEPTH_CLAMP): lit unless a caster is
  // nearer. A face that was not drawn has no receiver (light_views): lit.
  if (cube_map == 1) {
    int face = cube_face_of(world_position - light.xyz);
    vec4 c = cube_light_to_clip[face] * vec4(world_position, 1.0);
    if ((cube_faces & (1 << face)) != 0 && c.w > 0.0) {
      map_layer = face;
      view_of_light = cube_light_view[face];
      frustum_of_light = cube_light_frustum[face];
      vec3 w = (c.xyz / c.w) * 0.5 + 0.5;
      vec2 g = receiver_depth_gradient(window_derivative(cube_light_to_clip[face], c, dpx),
                                       window_derivative(cube_light_to_clip[face], c, dpy));
      amount = filtered_light(vec3(w.xy, clamp(w.z, 0.0, 1.0)), g, world_position);
    }
  } else if (clip.w > 0.0) {
    vec3 ndc = clip.xyz / clip.w;
    // textureLod inside: no derivatives needed (one level) in this non-uniform branch.
    if (all(lessThanEqual(abs(ndc), vec3(1.0)))) amount = filtered_light(window, gradient, world_position);
  }
  if (light_image_pass == 1) {
    fragment = vec4(amount, 0.0, 0.0, 0.0);
    return;
  }
  if (amount <= 0.0) discard;
  fragment = vec4(surface_albedo * colour.rgb * lambert * lambert_weight * amount, 0.0);
}
