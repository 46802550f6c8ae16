// Compiling and linking GLSL programs in the current GL context. Errors name
// the shader file and line, e.g. "shaders/gouraud.frag:12: 'x' undeclared".
#pragma once

#include <string>

namespace bounce::gl {

struct shader_source {
  std::string name;  // file name, used in messages
  std::string text;
};

// Compiles and links a vertex + fragment program. Returns the program id,
// or 0 with `error` set (one line per compiler message, file:line: text).
unsigned int make_program(const shader_source& vertex, const shader_source& fragment, std::string& error);

// Rewrites a driver's info log ("0:12(5): error: ..." from Mesa, or
// "ERROR: 0:12: ..." from others) so each message starts with name:line.
std::string format_shader_log(const std::string& name, const std::string& log);

}  // namespace bounce::gl
