// A point light's cube map (gpu/shadow_map_renderer.h's light_views): six 90-degree faces, each
// a layer of the array textures below, drawn with its own matrices; the lit pass picks, per
// fragment, the face its direction from the light falls in and reads that layer.
//
// The face of a direction d from the light: the axis of d's largest |component| (ties to the
// first axis, x before y before z), then its sign: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. Every
// direction gets one face, and a face's frustum (half angle atan(1.02), a little over 45 degrees)
// holds every direction of its face.
int cube_face_of(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
  return d.z >= 0.0 ? 4 : 5;
}

// The window coordinates' derivative along a screen step that moves the world point by dp, for
// the point whose light clip coordinates under `to_clip` are `c`: the chain rule through the
// perspective division. A cube face's window coordinates are not continuous across a quad whose
// fragments pick different faces, so the receiver-plane gradient is taken from the world
// position's derivatives (uniform control flow) and this, per fragment.
vec3 window_derivative(mat4 to_clip, vec4 c, vec3 dp) {
  vec4 dc = to_clip * vec4(dp, 0.0);
  return 0.5 * (dc.xyz * c.w - c.xyz * dc.w) / (c.w * c.w);
}
