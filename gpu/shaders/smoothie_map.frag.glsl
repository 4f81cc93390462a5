#version 450 core
// The nearest smoothie per texel (the depth test keeps it; no blending, Chen & Tsai §2.4 and §3):
// its alpha and its linear depth b from the light.
layout(location = 0) in float alpha;
layout(location = 1) in float depth;
layout(location = 0) out vec2 smoothie;

void main() { smoothie = vec2(alpha, depth); }
