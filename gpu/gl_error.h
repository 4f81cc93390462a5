#pragma once
// A GL call failed at run time (an invalid enum, a shader that does not compile...).
// Errors never throw from inside the driver's debug callback (C code is on the stack
// there): the callback records them and check_gl_errors() throws at the next check point,
// with the caller's `where` and the driver's own messages.
#include <stdexcept>
#include <string>

namespace shadowcert::gpu {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Drains glGetError() and the current context's debug log (gpu/detail/gl_debug_output.h);
// throws GlError "WHERE: GL_INVALID_OPERATION; driver: <message>" when anything was pending.
// Needs a current context.
void check_gl_errors(const char* where);

// "GL_INVALID_ENUM" for 0x0500, "GL error 0x1234" for codes it does not know.
[[nodiscard]] std::string gl_error_name(unsigned int code);

}  // namespace shadowcert::gpu
