#version 450 core
// The `ts` volume (gpu/tessellation_volume.h): one patch of kRecordWords vertices per record;
// each patch vertex is one word of the record (attribute 0, an unsigned integer), handed on
// to the tessellation control shader as it is (Milet 2014, Figure 4: the patch is indices).
layout(location = 0) in uint word;
flat out uint record_word;
flat out uint word_index;  // gl_VertexID: which record the patch is (deferral names it by this)

void main() {
  record_word = word;
  word_index = uint(gl_VertexID);
}
