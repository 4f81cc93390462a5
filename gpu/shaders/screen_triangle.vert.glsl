#version 450 core
// One triangle that covers the viewport (vertices 0, 1, 2 of an empty vertex array): the
// screen-aligned quad of the paper's image passes. Fragment shaders address texels by
// gl_FragCoord, so no texture coordinate is passed.
void main() {
  const vec2 corners[3] = vec2[3](vec2(-1.0, -1.0), vec2(3.0, -1.0), vec2(-1.0, 3.0));
  gl_Position = vec4(corners[gl_VertexID], 0.0, 1.0);
}
