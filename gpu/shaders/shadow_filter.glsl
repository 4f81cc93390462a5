// How much of a light reaches a visible point, by the shadow map family's filters
// (gpu/shadow_map_renderer.h, docs/smoothies.md): included by shadow_map_scene.frag.glsl after
// its `shadow_map` (sampler2DShadow, GL_LEQUAL: 1 = lit) and `depth_bias` declarations. The
// filters read the map through map_compare, map_depth and smoothie_texel, which a cube-mapped
// light points at one layer of its cube map (map_layer, below).
//   hard      one comparison at the point's texel (the `shadowmap` method, unchanged);
//   pcf       K x K comparisons at whole-texel offsets around it, averaged;
//   pcss      Fernando 2005: the blockers' mean depth in the region the light's disk (radius R)
//             sees through the point, then PCF over the penumbra that depth predicts;
//   smoothie  Chen & Tsai §3: the hard comparison (stage 1), then the nearest smoothie in front of
//             the point (stage 2) gives its alpha remapped, a' = a / (1 - b / r), clamped.
// Receiver-plane depth bias (Isidoro, "Shadow mapping: GPU-based tips and techniques", GDC 2006):
// the filters compare taps away from the point's own texel, where the receiver's own surface lies
// at another depth than at the point; each tap's reference depth follows the receiver's plane,
// window.z + dot(depth_gradient, offset), the gradient dz / d(uv) from the fragment's screen
// derivatives (shadow_map_scene.frag.glsl). Without it a wide PCF or PCSS kernel on a receiver
// tilted to the light compares against its own surface: acne over whole lit floors.
// Light-space lengths: z is the depth along the light's axis (-z of light_view), linear;
// one unit of the map's texture coordinates spans 2 z tan(half angle) world units at depth z
// under a point light, 2 half_width (2 half_height) under a directional light's box.
layout(location = 6) uniform int filter_mode;      // 0 hard, 1 pcf, 2 pcss, 3 smoothie
layout(location = 7) uniform int pcf_kernel;       // pcf: K, odd
layout(location = 8) uniform mat4 light_view;      // world to the light's view
layout(location = 9) uniform vec4 light_frustum;   // near, far, tan(half angle) or half width, half height
layout(location = 10) uniform int orthographic;    // 1: directional light (orthographic map)
layout(location = 11) uniform float light_radius;  // pcss: R (point: world units; directional: tangent)
layout(binding = 1) uniform sampler2D depth_values;  // the same map read without comparison (pcss)
layout(binding = 2) uniform sampler2D smoothie_map;  // (alpha, b) of the nearest smoothie; alpha < 0: none
// A point light's cube map (cube_face.glsl): the same three, one layer per face.
layout(binding = 3) uniform sampler2DArrayShadow cube_shadow_map;
layout(binding = 4) uniform sampler2DArray cube_depth_values;
layout(binding = 5) uniform sampler2DArray cube_smoothie_map;

// The map the filters read for this fragment: the light's one map (map_layer < 0: shadow_map,
// depth_values, smoothie_map) or layer map_layer of its cube map, with that view's matrix and
// frustum (the main function sets them before filtered_light).
int map_layer = -1;
mat4 view_of_light;
vec4 frustum_of_light;

// One hardware comparison (1 lit, 0 shadowed) at texture coordinates uv against depth ref. A
// single-level map: textureGrad with zero derivatives reads level 0 in any control flow.
float map_compare(vec2 uv, float ref) {
  if (map_layer < 0) return textureLod(shadow_map, vec3(uv, ref), 0.0);
  return textureGrad(cube_shadow_map, vec4(uv, float(map_layer), ref), vec2(0.0), vec2(0.0));
}
// The stored depth at uv, without comparison (pcss's blocker search).
float map_depth(vec2 uv) {
  if (map_layer < 0) return textureLod(depth_values, uv, 0.0).r;
  return textureLod(cube_depth_values, vec3(uv, float(map_layer)), 0.0).r;
}
ivec2 map_size() { return map_layer < 0 ? textureSize(shadow_map, 0) : textureSize(cube_shadow_map, 0).xy; }
vec2 smoothie_texel(ivec2 texel) {
  if (map_layer < 0) return texelFetch(smoothie_map, texel, 0).rg;
  return texelFetch(cube_smoothie_map, ivec3(texel, map_layer), 0).rg;
}
ivec2 smoothie_size() {
  return map_layer < 0 ? textureSize(smoothie_map, 0) : textureSize(cube_smoothie_map, 0).xy;
}

const int kFilterHard = 0;
const int kFilterPcf = 1;
const int kFilterPcss = 2;
const int kFilterSmoothie = 3;
// PCSS samples: a regular grid of this many taps per axis for the blocker search and for the
// filter (Fernando's reference shader uses 16 to 32 Poisson taps; a grid repeats exactly).
const int kPcssSearchTaps = 5;
const int kPcssFilterTaps = 7;
// The blocker search region, in texture coordinates, never exceeds this half width: a light
// disk seen from far behind the near plane would otherwise search most of the map (a cost
// bound, not a tolerance).
const float kPcssMaxSearchRadius = 0.125;
// A receiver counts as behind the nearest smoothie when r > b (1 + this): it absorbs the float
// rounding of the two depths (about 1e-7 relative) and the texel-centre versus point difference
// of b on a smoothie that touches the receiver, where b / r -> 1 would divide by rounding noise.
const float kSmoothieBehindTolerance = 1.0e-4;

// The receiver's depth gradient dz / d(uv) in the map, by its screen derivatives: `dx` and `dy` are
// dFdx and dFdy of the point's window coordinates. A plane's window depth is affine in the map's
// uv, so the gradient extrapolates the receiver's own depth exactly over a filter's taps, however
// steep: it is not clamped (a clamp made a steep floor count itself as its blocker, and PCSS's
// penumbra collapsed to a hard edge). Zero where the derivatives are degenerate or not finite
// (the receiver seen edge-on from the eye or from the light).
vec2 receiver_depth_gradient(vec3 dx, vec3 dy) {
  float det = dx.x * dy.y - dx.y * dy.x;
  if (!(abs(det) > 0.0)) return vec2(0.0);
  vec2 g = vec2(dy.y * dx.z - dx.y * dy.z, dx.x * dy.z - dy.x * dx.z) / det;
  if (isnan(g.x) || isnan(g.y) || isinf(g.x) || isinf(g.y)) return vec2(0.0);
  return g;
}

// The light's window depth d in [0, 1] as a linear depth along the light's axis.
float linear_depth(float d) {
  float near = frustum_of_light.x, far = frustum_of_light.y;
  if (orthographic == 1) return near + d * (far - near);
  return 2.0 * near * far / (far + near - (2.0 * d - 1.0) * (far - near));
}

// World units per unit of texture coordinate at linear depth z, per axis.
vec2 world_per_uv(float z) {
  if (orthographic == 1) return 2.0 * frustum_of_light.zw;
  return vec2(2.0 * z * frustum_of_light.z);
}

float hard_light(vec3 window) {
  return map_compare(window.xy, window.z - depth_bias) < 0.5 ? 0.0 : 1.0;
}

// taps x taps comparisons on a grid spanning [-radius, radius] around uv (one at uv when taps = 1),
// each against the receiver's plane there.
float grid_light(vec2 uv, float reference, vec2 gradient, vec2 radius, int taps) {
  float lit = 0.0;
  for (int i = 0; i < taps; ++i) {
    for (int j = 0; j < taps; ++j) {
      vec2 offset = taps == 1 ? vec2(0.0) : (vec2(i, j) * (2.0 / float(taps - 1)) - 1.0) * radius;
      lit += map_compare(uv + offset, reference + dot(gradient, offset));
    }
  }
  return lit / float(taps * taps);
}

float pcf_light(vec3 window, vec2 gradient) {
  vec2 texel = 1.0 / vec2(map_size());
  int half_kernel = (pcf_kernel - 1) / 2;
  float lit = 0.0;
  for (int i = -half_kernel; i <= half_kernel; ++i)
    for (int j = -half_kernel; j <= half_kernel; ++j) {
      vec2 offset = vec2(i, j) * texel;
      lit += map_compare(window.xy + offset, window.z - depth_bias + dot(gradient, offset));
    }
  return lit / float(pcf_kernel * pcf_kernel);
}

float pcss_light(vec3 window, vec2 gradient, float receiver_depth) {
  float near = frustum_of_light.x;
  float reference = window.z - depth_bias;
  // 1. Blocker search: the light's disk seen from the receiver, where the cone crosses the near
  //    plane (the widest place a blocker can be).
  float search_world = orthographic == 1 ? light_radius * (receiver_depth - near)
                                         : light_radius * (receiver_depth - near) / receiver_depth;
  vec2 search = min(vec2(search_world) / world_per_uv(near), vec2(kPcssMaxSearchRadius));
  float blocker_sum = 0.0;
  int blockers = 0;
  for (int i = 0; i < kPcssSearchTaps; ++i) {
    for (int j = 0; j < kPcssSearchTaps; ++j) {
      vec2 offset = (vec2(i, j) * (2.0 / float(kPcssSearchTaps - 1)) - 1.0) * search;
      float d = map_depth(window.xy + offset);
      // The point's own reference, not the receiver's plane: the search region is wide (the
      // light's disk at the near plane), and over it the plane reaches casters far from the
      // point, which then count as its blockers; a texel of the receiver itself that the plane
      // would have excused only pulls the mean blocker depth towards the receiver (a narrower
      // penumbra), never darkens.
      if (d < reference) {
        blocker_sum += linear_depth(d);
        ++blockers;
      }
    }
  }
  if (blockers == 0) return 1.0;
  float blocker_depth = blocker_sum / float(blockers);
  // 2. The penumbra's half width at the receiver (similar triangles), then PCF over it.
  float penumbra_world = orthographic == 1 ? light_radius * (receiver_depth - blocker_depth)
                                           : light_radius * (receiver_depth - blocker_depth) / blocker_depth;
  vec2 radius = max(vec2(penumbra_world), vec2(0.0)) / world_per_uv(receiver_depth);
  return grid_light(window.xy, reference, gradient, radius, kPcssFilterTaps);
}

float smoothie_light(vec3 window, float receiver_depth) {
  if (hard_light(window) == 0.0) return 0.0;  // stage 1: the shadow map says shadowed
  ivec2 size = smoothie_size();
  ivec2 texel = clamp(ivec2(window.xy * vec2(size)), ivec2(0), size - 1);
  vec2 smoothie = smoothie_texel(texel);  // alpha, b
  // Stage 2: no smoothie, or none in front of the point: lit.
  if (smoothie.x < 0.0 || !(receiver_depth > smoothie.y * (1.0 + kSmoothieBehindTolerance))) return 1.0;
  return clamp(smoothie.x / (1.0 - smoothie.y / receiver_depth), 0.0, 1.0);
}

// The amount of the light that reaches world point p, whose light window coordinates are `window`
// and whose receiver's depth gradient in the map is `gradient` (receiver_depth_gradient).
float filtered_light(vec3 window, vec2 gradient, vec3 p) {
  if (filter_mode == kFilterHard) return hard_light(window);
  if (filter_mode == kFilterPcf) return pcf_light(window, gradient);
  float receiver_depth = -(view_of_light * vec4(p, 1.0)).z;
  if (filter_mode == kFilterPcss) return pcss_light(window, gradient, receiver_depth);
  return smoothie_light(window, receiver_depth);
}
