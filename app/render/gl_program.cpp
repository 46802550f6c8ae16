#include "render/gl_program.h"

#include <regex>
#include <sstream>

#include <glad/gl.h>

namespace bounce::gl {

std::string format_shader_log(const std::string& name, const std::string& log) {
  // Mesa: "0:12(5): error: msg"; NVIDIA/AMD style: "ERROR: 0:12: msg" or "0(12) : error C0000: msg".
  static const std::regex mesa(R"(^\s*\d+:(\d+)\(\d+\):\s*(.*)$)");
  static const std::regex khronos(R"(^\s*(?:ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*\d+\((\d+)\)\s*:\s*(.*)$)");
  std::istringstream in(log);
  std::ostringstream out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::smatch m;
    if (std::regex_match(line, m, mesa) || std::regex_match(line, m, khronos) || std::regex_match(line, m, nvidia))
      out << name << ":" << m[1] << ": " << m[2] << "\n";
    else
      out << name << ": " << line << "\n";
  }
  return out.str();
}

namespace {

GLuint compile(GLenum stage, const shader_source& source, std::string& error) {
  GLuint shader = glCreateShader(stage);
  const char* text = source.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  error += format_shader_log(source.name, log.c_str());
  glDeleteShader(shader);
  return 0;
}

}  // namespace

unsigned int make_program(const shader_source& vertex, const shader_source& fragment, std::string& error) {
  error.clear();
  GLuint vs = compile(GL_VERTEX_SHADER, vertex, error);
  GLuint fs = compile(GL_FRAGMENT_SHADER, fragment, error);
  if (!vs || !fs) {
    if (vs) glDeleteShader(vs);
    if (fs) glDeleteShader(fs);
    return 0;
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);  // flagged; freed with the program
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return program;
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  error = vertex.name + " + " + fragment.name + ": link failed: " + log.c_str();
  glDeleteProgram(program);
  return 0;
}

}  // namespace bounce::gl
