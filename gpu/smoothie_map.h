#pragma once
// The smoothie map (Chen & Tsai §3, Chan & Durand 2003; docs/smoothies.md): a light's smoothies
// (core/smoothie_mesh.h, built by contour/smoothie.h) drawn from the light with the shadow map's
// own matrix into an RG32F texture of the shadow map's size: per texel the alpha and the linear
// depth b of the NEAREST smoothie (depth test GL_LESS, no blending: blended alphas grow, §2.4).
// Texels no smoothie covers hold (kNoSmoothieAlpha, 0). GL_DEPTH_CLAMP is on, so a smoothie that
// leaves the map's depth range (a bisector towards the light) is kept, at the range's end, with its
// own b. gpu/shadow_map_renderer.cpp reads it in the `smoothie` method's lit pass.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/smoothie_mesh.h"
#include "gpu/gl_object.h"

namespace shadowcert::gpu {

inline constexpr float kNoSmoothieAlpha = -1.0f;

// A smoothie mesh on the GPU: one vec4 per vertex (world position rounded once to float, alpha),
// an index buffer and a vertex array.
class SmoothieQuads {
 public:
  // Throws std::invalid_argument("SmoothieQuads: ...") when alpha does not have one entry per
  // vertex or an index is out of range; GlError from the driver.
  explicit SmoothieQuads(const SmoothieMesh& mesh);

  [[nodiscard]] GLuint vertex_array() const { return vertex_array_.name(); }
  [[nodiscard]] GLsizei index_count() const { return index_count_; }
  [[nodiscard]] std::uint64_t triangles() const { return static_cast<std::uint64_t>(index_count_) / 3; }

 private:
  Buffer vertices_;
  Buffer indices_;
  VertexArray vertex_array_;
  GLsizei index_count_ = 0;
};

class SmoothieMap {
 public:
  // Allocates the size x size map and compiles smoothie_map.{vert,frag}.glsl. Throws
  // std::invalid_argument for size 0, GlError from the driver.
  explicit SmoothieMap(std::uint32_t size);

  // Clears the map and draws `quads` with `light_to_clip` (gpu/shadow_map_renderer.h's
  // LightFrustum) and `light_view` (its view matrix, for b). Leaves its framebuffer bound.
  void render(const SmoothieQuads& quads, const glm::mat4& light_to_clip, const glm::mat4& light_view) const;

  // The RG32F texture: (alpha, b) per texel, for texelFetch.
  [[nodiscard]] GLuint texture() const { return texture_.name(); }
  [[nodiscard]] std::uint32_t size() const { return size_; }
  // The map read back (tests): 2 floats per texel, row 0 at the BOTTOM (the light's image as GL
  // stores it).
  [[nodiscard]] std::vector<float> read() const;

 private:
  std::uint32_t size_;
  Texture texture_;
  Renderbuffer depth_;
  Framebuffer framebuffer_;
  Program program_;
};

}  // namespace shadowcert::gpu
