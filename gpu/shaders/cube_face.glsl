// The face of a point light's cube map (gpu/shadow_map_renderer.h's light_views) that the
// direction d from the light falls in: the axis of d's largest |component| (ties to the first
// axis, x before y before z), then its sign: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z. Every direction
// gets one face, the same in every pass (the same expression on the same inputs), so that the
// six lit passes of a cube-mapped light light each fragment exactly once. A face's frustum
// (half angle atan(kFitMargin) > 45 degrees) holds every direction of its face.
int cube_face_of(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
  return d.z >= 0.0 ? 4 : 5;
}
