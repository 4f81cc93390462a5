#include "gpu/shader_compiler.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/gl_error.h"

namespace shadowcert::gpu {
namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

Shader compile_sources(GLenum stage, std::initializer_list<std::string_view> sources, std::string_view name) {
  Shader shader = Shader::create(stage);
  if (!shader) throw GlError(std::string(name) + ": glCreateShader failed (bad stage?)");
  std::vector<const GLchar*> texts;
  std::vector<GLint> lengths;
  for (std::string_view s : sources) {
    texts.push_back(s.data());
    lengths.push_back(static_cast<GLint>(s.size()));
  }
  glShaderSource(shader.name(), static_cast<GLsizei>(texts.size()), texts.data(), lengths.data());
  glCompileShader(shader.name());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.name(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) throw GlError(std::string(name) + ": GLSL compile error:\n" + shader_log(shader.name()));
  check_gl_errors(std::string(name).c_str());
  return shader;
}

}  // namespace

Shader compile_shader(GLenum stage, std::string_view source, std::string_view name) {
  return compile_sources(stage, {source}, name);
}

Shader compile_shader(GLenum stage, std::string_view source, std::string_view name, std::string_view defines) {
  if (defines.empty()) return compile_sources(stage, {source}, name);
  const std::size_t first_line_end = source.find('\n');
  if (!source.starts_with("#version") || first_line_end == std::string_view::npos)
    throw std::invalid_argument("compile_shader: " + std::string(name) + " does not start with a #version line");
  // The #version line, the defines, the rest (the driver's line numbers then count the
  // defines' lines too).
  return compile_sources(stage, {source.substr(0, first_line_end + 1), defines, source.substr(first_line_end + 1)},
                         name);
}

Program link_program(std::initializer_list<const Shader*> shaders, std::string_view name) {
  Program program = Program::create();
  for (const Shader* s : shaders) glAttachShader(program.name(), s->name());
  glLinkProgram(program.name());
  for (const Shader* s : shaders) glDetachShader(program.name(), s->name());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.name(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) throw GlError(std::string(name) + ": GLSL link error:\n" + program_log(program.name()));
  check_gl_errors(std::string(name).c_str());
  return program;
}

}  // namespace shadowcert::gpu
