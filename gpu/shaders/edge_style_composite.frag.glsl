#version 450 core
// An edge-map style's composite (gpu/edge_style.h): the shaded scene (edge_style_shade.frag.glsl)
// with the edge map (gpu/edge_map.h) over it, over white paper where no surface is. Each
// intensity becomes a blending weight through its threshold (edge_weight below); then, as the
// paper's technical illustrations do (§5), the inner edges blend towards their colour and the
// profile edges towards black over that:
//   style 0, edges: inner kEdgesInnerColour (grey), profile black
//   style 1, gooch: inner white, profile black (Nienhaus & Doellner, Fig. 7)
//   style 2, toon:  inner and profile black; the shaded scene is the cartoon map, anti-aliased
//            here by a 3 x 3 tent over its covered texels (the paper's smoothing of the
//            colour patches' jagged boundaries, Fig. 9)
layout(binding = 0) uniform sampler2D shade;     // RGBA8; alpha 1 where a surface is
layout(binding = 1) uniform sampler2D edge_map;  // RGBA32F: profile, inner, covered, 1
layout(location = 0) uniform int style;
layout(location = 1) uniform vec2 thresholds;    // (profile, inner)
layout(location = 0) out vec4 colour;

const vec3 kPaper = vec3(1.0);
const vec3 kEdgesInnerColour = vec3(0.45);

// 0 up to the threshold (what is not an edge pixel is not drawn), 1 from twice the threshold
// on, linear between: the thresholded edge map with a ramp above it that keeps the filters'
// anti-aliased intensities (the paper blends by the raw intensity). A threshold of 0 draws every
// nonzero intensity fully.
float edge_weight(float intensity, float threshold) {
  if (threshold <= 0.0) return intensity > 0.0 ? 1.0 : 0.0;
  return clamp((intensity - threshold) / threshold, 0.0, 1.0);
}

vec4 shade_at(ivec2 p) {
  return texelFetch(shade, clamp(p, ivec2(0), textureSize(shade, 0) - ivec2(1)), 0);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 s = shade_at(p);
  vec3 base = s.a > 0.5 ? s.rgb : kPaper;
  if (style == 2 && s.a > 0.5) {
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        vec4 t = shade_at(p + ivec2(dx, dy));
        if (t.a <= 0.5) continue;
        float k = float((2 - abs(dx)) * (2 - abs(dy)));  // 4 at the centre, 2 beside, 1 diagonal
        sum += k * t.rgb;
        weights += k;
      }
    }
    base = sum / weights;
  }
  vec4 e = texelFetch(edge_map, p, 0);
  vec3 inner_colour = style == 1 ? vec3(1.0) : style == 2 ? vec3(0.0) : kEdgesInnerColour;
  vec3 c = mix(base, inner_colour, edge_weight(e.g, thresholds.y));
  c = mix(c, vec3(0.0), edge_weight(e.r, thresholds.x));
  colour = vec4(c, 1.0);
}
