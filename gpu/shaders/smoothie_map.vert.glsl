#version 450 core
// The smoothie map (gpu/smoothie_map.h; docs/smoothies.md): a light's smoothies seen from the
// light, with the shadow map's own light_to_clip (gpu/shadow_map_renderer.h). Attribute 0 holds
// the world position and the smoothie's alpha (0 on the silhouette edge, 1 on the outer rim).
layout(location = 0) in vec4 vertex;
layout(location = 0) uniform mat4 light_to_clip;
layout(location = 1) uniform mat4 light_view;  // world to the light's view: -z is the linear depth
layout(location = 0) out float alpha;
layout(location = 1) out float depth;

void main() {
  vec4 position = vec4(vertex.xyz, 1.0);
  gl_Position = light_to_clip * position;
  alpha = vertex.w;
  // Affine in world space, so perspective-correct interpolation gives each fragment its own
  // distance along the light's axis (Chan & Durand's b, measured as the light map's depth).
  depth = -(light_view * position).z;
}
