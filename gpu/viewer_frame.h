#pragma once
// One frame of `shadowcert view` (cli/view_command.cpp): the viewer is a host of
// gpu/host_shadow_volumes.h like any engine, whose own passes are those of shadowcert's
// offscreen renderer (clear to (0, 0, 0, 0), the depth pass in ambient colour through
// gpu/stencil_passes.h's program), so that its frame equals `shadowcert render`'s pixel for
// pixel at the same size; then optionally an RGBA overlay; then the frame is copied to the
// window (glBlitFramebuffer, same size, GL_NEAREST: the bytes as drawn). It draws into a
// framebuffer of its own, as an engine draws into its render targets, and not into the
// window's: Mesa's window buffers are stored upside down, and the rasteriser's fill rule then
// gives a pixel on an edge shared by two triangles to the other one (4 pixels of 160x120
// differed on default.json). Every GL call of the viewer is here: cli/ sees GLFW, never GL.
//
//   ViewerFrame frame(drawn.parts);                   // the receivers, uploaded
//   frame.draw(camera, shadows);                      // into framebuffer 0, every light
//   frame.draw_overlay(overlay);                      // the exact image's verdicts, blended
//   RgbaImage shot = frame.read_colour(w, h);         // the back buffer, row 0 at the top
#include <cstdint>
#include <memory>
#include <span>

#include "core/camera.h"
#include "gpu/gl_object.h"
#include "gpu/host_shadow_volumes.h"
#include "gpu/image.h"
#include "gpu/offscreen_target.h"
#include "gpu/stencil_shadow_renderer.h"

namespace shadowcert::gpu {

class ShadowSceneProgram;

class ViewerFrame {
 public:
  // `parts`: the receivers (read once, uploaded); width x height: the frame's and the
  // window's size. Needs a current context; throws GlError.
  ViewerFrame(std::span<const ShadedSoupPart> parts, std::uint32_t width, std::uint32_t height);
  ~ViewerFrame();
  ViewerFrame(const ViewerFrame&) = delete;
  ViewerFrame& operator=(const ViewerFrame&) = delete;

  // Into the frame's own framebuffer (camera.width x camera.height, the constructor's): clear, depth and ambient,
  // then every light of `shadows` lit where its count is 0, each with the offscreen
  // renderer's share of the light colour. Queues only (no wait).
  void draw(const Camera& camera, const HostShadowVolumes& shadows) const;
  // `overlay` (the frame's size) blended over the frame's colour by its alpha, whatever
  // framebuffer is bound; the alpha channel of the frame is kept. Throws
  // std::invalid_argument on another size.
  void draw_overlay(const RgbaImage& overlay) const;
  // The frame copied to the window's back buffer (framebuffer 0).
  void present() const;
  // The window's back buffer after present(), row 0 at the top (waits).
  [[nodiscard]] RgbaImage read_colour() const;

 private:
  OffscreenTarget target_;
  ShadedSoupMesh receivers_;
  std::unique_ptr<ShadowSceneProgram> program_;
  Program overlay_program_;
  VertexArray empty_;
};

}  // namespace shadowcert::gpu
