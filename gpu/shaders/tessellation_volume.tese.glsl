#version 450 core
// The `ts` volume (gpu/tessellation_volume.h): |m| isolines of one segment per edge record
// (one line per triangle record). Milet's evaluation shader bends a tessellated quad into |m|
// overlapping quads; here each isoline is one copy, and the geometry shader turns it into the
// quad's two triangles in cs's vertex order (a tessellator's own quad triangulation would not
// keep that order, which llvmpipe's clipping of w = 0 vertices is sensitive to).
layout(isolines, equal_spacing) in;

patch in uvec4 item;
patch in int multiplicity;

flat out uvec4 line_item;
flat out int line_multiplicity;

void main() {
  line_item = item;
  line_multiplicity = multiplicity;
  gl_Position = vec4(gl_TessCoord.xy, 0.0, 1.0);  // unused: nothing is rasterised
}
