#version 450 core
// Ambient pass (lambert_weight = 0): albedo * colour, alpha 1 marks covered pixels.
// Lit pass (lambert_weight = 1): albedo * colour * max(n . d, 0), alpha 0, added by
// blending where the stencil count is 0. Soups have no trustworthy orientation (docs/definitions.md#inputs
// ), so the normal is turned towards the viewer (two-sided lighting).
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec3 surface_albedo;
layout(location = 1) uniform vec4 colour;
layout(location = 2) uniform vec4 light;       // (l, w): w = 1 point, w = 0 directional
layout(location = 3) uniform float lambert_weight;
layout(location = 0) out vec4 fragment;

void main() {
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
    if (d_length > 0.0) lambert = max(dot(n, to_light / d_length), 0.0);
  }
  fragment = vec4(surface_albedo * colour.rgb * lambert * lambert_weight, 0.0);
}
