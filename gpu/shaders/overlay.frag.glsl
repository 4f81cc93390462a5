#version 450 core
// An RGBA image over the frame (`shadowcert view`'s exact-image overlay, gpu/viewer_frame.h):
// one texel per pixel, row 0 at the TOP (gpu/image.h), blended by its alpha.
layout(binding = 0) uniform sampler2D overlay;
layout(location = 0) out vec4 fragment;

void main() {
  ivec2 size = textureSize(overlay, 0);
  ivec2 p = ivec2(gl_FragCoord.xy);
  fragment = texelFetch(overlay, ivec2(p.x, size.y - 1 - p.y), 0);
}
