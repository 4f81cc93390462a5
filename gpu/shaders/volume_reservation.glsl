// Included (cmake/EmbedShaders.cmake) before far_split.glsl by the compute shaders that write
// volume triangles into a storage buffer themselves: cs (compute_volume.comp.glsl) and ts's
// finish pass (tessellation_volume_finish.comp.glsl). The includer declares `vec4 volume[]`
// (3 vec4 per triangle), the coherent `uint requested` of its draw command (vertices asked for)
// and `uniform uint capacity` (vertices the buffer holds).

const uint kNoRoom = 0xFFFFFFFFu;

// Where volume_triangle writes next (set after each reservation).
uint volume_cursor = 0u;

// far_split.glsl's output: one triangle of the volume at the cursor.
void volume_triangle(vec4 a, vec4 b, vec4 c) {
  volume[volume_cursor] = a;
  volume[volume_cursor + 1u] = b;
  volume[volume_cursor + 2u] = c;
  volume_cursor += 3u;
}

// Reserves n vertices; kNoRoom when they do not fit (the count still records the request, so an
// overflow is reported, never drawn past).
uint reserve(uint n) {
  const uint base = atomicAdd(requested, n);
  return (n <= capacity && base <= capacity - n) ? base : kNoRoom;
}
