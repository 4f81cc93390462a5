#pragma once
// The camera of the flat-soup and camera-transform tests: a 64x64 view where world (X, Y, 0)
// lands at image ((X/5 + 1) * 32, (1 - Y/5) * 32): fov 90 degrees at distance 5 spans [-5, 5]
// both ways.
#include "core/camera.h"

namespace shadowcert::gpu {

inline Camera square_test_camera() {
  Camera camera;
  camera.eye = {0.0, 0.0, 5.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.up = {0.0, 1.0, 0.0};
  camera.fov_y_degrees = 90.0;
  camera.width = 64;
  camera.height = 64;
  return camera;
}

}  // namespace shadowcert::gpu
