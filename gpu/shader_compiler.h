#pragma once
// Shaders from their GLSL text (the embedded gpu/shaders/*.glsl) to a linked program.
// Failures throw GlError with the shader's (or program's) name and the driver's info log,
// the only place a GLSL mistake is explained.
#include <initializer_list>
#include <string_view>

#include "gpu/gl_object.h"

namespace shadowcert::gpu {

// `name` identifies the source in messages, e.g. "flat_colour.vert.glsl".
[[nodiscard]] Shader compile_shader(GLenum stage, std::string_view source, std::string_view name);
// The same with `defines` (lines such as "#define X 1\n") inserted after the source's first
// line, which GLSL requires to be its #version directive (std::invalid_argument otherwise).
[[nodiscard]] Shader compile_shader(GLenum stage, std::string_view source, std::string_view name,
                                    std::string_view defines);

// Links, then detaches the shaders so that deleting them frees them at once.
[[nodiscard]] Program link_program(std::initializer_list<const Shader*> shaders, std::string_view name);

}  // namespace shadowcert::gpu
