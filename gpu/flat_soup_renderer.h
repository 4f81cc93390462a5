#pragma once
// The smallest proof that the pipeline draws: a soup's triangles in one colour, seen
// by a Camera, into the bound OffscreenTarget; optionally counting, per pixel, the
// triangles drawn there in the stencil buffer (the operation shadow volumes build on).
#include <array>

#include "core/camera.h"
#include "gpu/gl_object.h"
#include "gpu/soup_mesh.h"

namespace shadowcert::gpu {

struct FlatDrawOptions {
  std::array<float, 4> colour{1.0f, 1.0f, 1.0f, 1.0f};
  bool depth_test = true;          // off: every triangle reaches every pixel it covers
  bool count_in_stencil = false;   // on: stencil += 1 (wrapping) per fragment drawn
};

class FlatSoupRenderer {
 public:
  FlatSoupRenderer();  // compiles flat_colour.{vert,frag}.glsl; throws GlError with the log

  // Draws into the currently bound framebuffer; both faces, no culling (soups have no
  // trustworthy orientation). Leaves depth/stencil state as it set it.
  void draw(const SoupMesh& mesh, const Camera& camera, const FlatDrawOptions& options = {}) const;

 private:
  Program program_;
};

}  // namespace shadowcert::gpu
