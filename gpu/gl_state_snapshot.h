#pragma once
// The GL state a host's context holds and shadowcert's passes change (docs/engine-integration.md,
// "State contract"): captured before a call into a host's context and put back after it, so
// that the host finds every binding, enable, function and mask as it left them.
//
//   {
//     const ScopedGlState keep;  // captures
//     ... shadowcert's passes ...
//   }                            // restores
//
// What is captured (and nothing else: the viewport, scissor box, textures, samplers, images,
// uniform buffers and the framebuffer bindings are never changed by the host layer, so they
// are neither read nor written):
//   bindings   current program, vertex array, GL_DRAW_INDIRECT_BUFFER, GL_ARRAY_BUFFER, the
//              transform feedback object, the generic GL_SHADER_STORAGE_BUFFER and
//              GL_TRANSFORM_FEEDBACK_BUFFER bindings and their indexed bindings
//              0..kSnapshotBufferBindings-1 (buffer, start, size), GL_PATCH_VERTICES
//   enables    depth test, stencil test, blend (per draw buffer), cull face, depth clamp,
//              polygon offset fill, rasterizer discard, alpha to coverage, sample coverage,
//              colour logic op, primitive restart (both), GL_MULTISAMPLE
//   functions  depth func and mask, front face, polygon mode, colour mask (per draw buffer),
//              stencil func, ref, masks and ops of both faces, the stencil clear value, blend
//              functions and equations (rgb, alpha)
// A snapshot is plain data: two snapshots compare equal when every captured value is equal,
// and differences() names the values that are not (the state contract's test).
#include <cstdint>
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace shadowcert::gpu {

// The indexed storage and transform feedback bindings captured: every binding point any
// shader of gpu/ declares is below this (compute_volume.comp.glsl uses 0..7, the finish
// passes up to 9); a host's bindings above it are never touched.
inline constexpr GLuint kSnapshotBufferBindings = 12;

class GlStateSnapshot {
 public:
  // Reads the state listed above from the current context (glGet*: no GPU wait on Mesa or
  // NVIDIA, which answer state queries from the client side).
  [[nodiscard]] static GlStateSnapshot capture();
  // Sets every captured value back.
  void restore() const;

  // One "name: before -> after" line per value that differs from `other`; empty when equal.
  [[nodiscard]] std::vector<std::string> differences(const GlStateSnapshot& other) const;
  [[nodiscard]] bool operator==(const GlStateSnapshot& other) const { return values_ == other.values_; }

 private:
  struct Value {
    std::string name;  // e.g. "GL_STENCIL_FUNC", "GL_SHADER_STORAGE_BUFFER_BINDING[3]"
    std::int64_t value = 0;
    bool operator==(const Value&) const = default;
  };
  void add(std::string name, std::int64_t value) { values_.push_back({std::move(name), value}); }
  [[nodiscard]] std::int64_t get(const std::string& name) const;
  std::vector<Value> values_;
};

// Captures on construction, restores on destruction (also when a pass throws).
class ScopedGlState {
 public:
  ScopedGlState() : saved_(GlStateSnapshot::capture()) {}
  ~ScopedGlState() { saved_.restore(); }
  ScopedGlState(const ScopedGlState&) = delete;
  ScopedGlState& operator=(const ScopedGlState&) = delete;

 private:
  GlStateSnapshot saved_;
};

}  // namespace shadowcert::gpu
