// Included (cmake/EmbedShaders.cmake resolves the include directive naming this file at build
// time) by reference_edge.glsl, which every shader that takes a sign includes: cs, gs, ts and
// pertri. It mirrors
// core/light_side_formula.h operation for operation (Milet 2014, Algorithm 4):
//   X = C - A;  Y = l - A w;  N = X x Y;  value = N . (B - A)
// with `precise` so no stage fuses or reorders it; the including shader declares
// `uniform vec4 light` (l, w). One copy, so the GPU methods cannot drift from the CPU formula.
float light_side_value(vec3 a, vec3 b, vec3 c) {
  precise float x0 = c.x - a.x;
  precise float x1 = c.y - a.y;
  precise float x2 = c.z - a.z;
  precise float y0 = light.x - a.x * light.w;
  precise float y1 = light.y - a.y * light.w;
  precise float y2 = light.z - a.z * light.w;
  precise float n0 = x1 * y2 - x2 * y1;
  precise float n1 = x2 * y0 - x0 * y2;
  precise float n2 = x0 * y1 - x1 * y0;
  precise float z0 = b.x - a.x;
  precise float z1 = b.y - a.y;
  precise float z2 = b.z - a.z;
  precise float value = n0 * z0 + n1 * z1 + n2 * z2;
  return value;
}
