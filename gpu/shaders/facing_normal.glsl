// Shared by the passes that shade or store a surface's normal for edge maps (g_buffer.frag.glsl,
// edge_style_shade.frag.glsl): the unit normal of the fragment turned towards the eye. Soups have
// no orientation (docs/definitions.md#inputs) and a soup's vertex normals need not agree with its
// triangles' winding, so the side is taken from the triangle's own plane as the eye sees it: its
// geometric normal from the screen derivatives of the position, pointed at the eye; the shading
// normal (interpolated vertex normal or face normal) is flipped to that side. A zero or
// non-finite shading normal (a degenerate triangle's face normal) gives the geometric one.
// `position` and `eye` in the same space.
vec3 facing_normal(vec3 position, vec3 shading_normal, vec3 eye) {
  vec3 to_eye = eye - position;
  vec3 geometric = cross(dFdx(position), dFdy(position));
  float g_length = length(geometric);
  geometric = g_length > 0.0 ? geometric / g_length : normalize(to_eye);
  if (dot(geometric, to_eye) < 0.0) geometric = -geometric;
  float n_length = length(shading_normal);
  if (!(n_length > 0.0) || isinf(n_length)) return geometric;
  vec3 n = shading_normal / n_length;
  return dot(n, geometric) < 0.0 ? -n : n;
}
