#version 450 core
// The `gs` volume (gpu/geometry_shader_volume.h): one point per edge record, then one per
// triangle, no attributes. The geometry shader fetches everything from storage buffers by this
// index, so the vertex stage only hands it on.
flat out uint item_id;

void main() {
  item_id = uint(gl_VertexID);
}
