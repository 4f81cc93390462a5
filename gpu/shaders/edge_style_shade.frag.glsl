#version 450 core
// The shaded scene of an edge-map style (gpu/edge_style.h), drawn with shadow_scene.vert.glsl
// into a texture that the composite (edge_style_composite.frag.glsl) puts the edges over:
//   style 0, edges: white paper; in shadow kEdgesShadowTone
//   style 1, gooch: Gooch et al. 1998's cool-to-warm tone, t = (1 + n . l) / 2 times the light's
//            amount: k_cool = (0, 0, 0.4) + 0.2 albedo, k_warm = (0.4, 0.4, 0) + 0.6 albedo,
//            colour = mix(k_cool, k_warm, t) (Nienhaus & Doellner §5, Technical Illustrations)
//   style 2, toon:  Lake et al. 2000: albedo times the 1D shade texture (nearest filtering) at
//            max(n . l, 0) times the light's amount (§5, Cartoon-Style Rendering)
// The light's amount (`light_amount`, a shadow method's first-light image, StencilShadowFrame::
// first_light) is 1 lit, 0 in shadow, between in a penumbra; without shadows it is 1. The
// alpha channel marks covered pixels (1); the texture is cleared to alpha 0.
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec3 surface_albedo;
layout(location = 1) uniform int style;
layout(location = 2) uniform vec4 light;           // (l, w): w = 1 point, w = 0 directional
layout(location = 3) uniform int has_light_amount;  // 0: lit everywhere
layout(location = 4) uniform vec3 eye;             // the camera's eye, world space
layout(binding = 0) uniform sampler2D light_amount;  // R32F, GL's rows; < 0 where no receiver
layout(binding = 1) uniform sampler1D toon_shades;   // R32F, GL_NEAREST, clamped
layout(location = 0) out vec4 fragment;

#include "facing_normal.glsl"

const float kEdgesShadowTone = 0.75;
const vec3 kGoochBlue = vec3(0.0, 0.0, 0.4), kGoochYellow = vec3(0.4, 0.4, 0.0);
const float kGoochAlpha = 0.2, kGoochBeta = 0.6;

void main() {
  vec3 n = facing_normal(world_position, world_normal, eye);
  vec3 to_light = light.w == 0.0 ? light.xyz : light.xyz - world_position;
  float d_length = length(to_light);
  float n_dot_l = d_length > 0.0 ? dot(n, to_light / d_length) : 0.0;
  float amount = 1.0;
  if (has_light_amount != 0) {
    float a = texelFetch(light_amount, ivec2(gl_FragCoord.xy), 0).r;
    amount = a < 0.0 ? 1.0 : clamp(a, 0.0, 1.0);
  }
  vec3 colour;
  if (style == 1) {
    vec3 k_cool = kGoochBlue + kGoochAlpha * surface_albedo;
    vec3 k_warm = kGoochYellow + kGoochBeta * surface_albedo;
    colour = mix(k_cool, k_warm, 0.5 * (1.0 + n_dot_l) * amount);
  } else if (style == 2) {
    colour = surface_albedo * texture(toon_shades, clamp(max(n_dot_l, 0.0) * amount, 0.0, 1.0)).r;
  } else {
    colour = vec3(mix(kEdgesShadowTone, 1.0, amount));
  }
  fragment = vec4(colour, 1.0);
}
