// The GL foundation, headless: an OSMesa core context, glad, and programs
// whose compile errors name the shader file and line.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include "headless/osmesa_context.h"
#include "render/gl_program.h"

namespace bounce {
namespace {

const gl::shader_source fullscreen_vs{"fullscreen.vert", R"(#version 330 core
// A triangle that covers the viewport, from gl_VertexID alone.
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)"};

const gl::shader_source colour_fs{"colour.frag", R"(#version 330 core
uniform vec4 colour;
out vec4 fragment;
void main() { fragment = colour; }
)"};

TEST(Headless, CoreContextThroughOsmesa) {
  headless::osmesa_context context(64, 32);
  ASSERT_TRUE(context.ok()) << context.error();
  EXPECT_NE(context.renderer().find("llvmpipe"), std::string::npos) << context.renderer();
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  EXPECT_GE(major, 3);
  GLint profile = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST(Headless, DrawsAndReadsBackTopRowFirst) {
  headless::osmesa_context context(64, 32);
  ASSERT_TRUE(context.ok()) << context.error();
  std::string error;
  GLuint program = gl::make_program(fullscreen_vs, colour_fs, error);
  ASSERT_NE(program, 0u) << error;
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glViewport(0, 0, 64, 32);
  glClearColor(0, 0, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  // Fill only the top half (GL's y points up) with the program's colour.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 16, 64, 16);
  glUseProgram(program);
  glUniform4f(glGetUniformLocation(program, "colour"), 1.0f, 0.5f, 0.0f, 1.0f);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  std::vector<unsigned char> rgba = context.read_rgba8();
  ASSERT_EQ(rgba.size(), 64u * 32u * 4u);
  const unsigned char* top = &rgba[(2 * 64 + 10) * 4];      // row 2 from the top
  const unsigned char* bottom = &rgba[(29 * 64 + 10) * 4];  // row 29 from the top
  EXPECT_EQ(top[0], 255);
  EXPECT_NEAR(top[1], 128, 1);
  EXPECT_EQ(top[2], 0);
  EXPECT_EQ(bottom[0], 0);
  EXPECT_EQ(bottom[2], 255);
  glDeleteProgram(program);
  glDeleteVertexArrays(1, &vao);
}

TEST(Headless, ShaderErrorsNameFileAndLine) {
  headless::osmesa_context context(8, 8);
  ASSERT_TRUE(context.ok()) << context.error();
  gl::shader_source broken{"broken.frag",
                           "#version 330 core\nout vec4 fragment;\nvoid main() {\n  fragment = undeclared;\n}\n"};
  std::string error;
  EXPECT_EQ(gl::make_program(fullscreen_vs, broken, error), 0u);
  EXPECT_NE(error.find("broken.frag:4: "), std::string::npos) << error;
  EXPECT_NE(error.find("undeclared"), std::string::npos) << error;
}

TEST(Headless, RefusesAbsurdSizes) {
  headless::osmesa_context context(100000, 10);
  EXPECT_FALSE(context.ok());
  EXPECT_NE(context.error().find("100000x10"), std::string::npos);
}

TEST(ShaderLog, DriverFormatsBecomeFileAndLine) {
  EXPECT_EQ(gl::format_shader_log("a.frag", "0:12(5): error: `x' undeclared\n"), "a.frag:12: error: `x' undeclared\n");
  EXPECT_EQ(gl::format_shader_log("a.vert", "ERROR: 0:7: 'foo' : syntax error\n"), "a.vert:7: 'foo' : syntax error\n");
  EXPECT_EQ(gl::format_shader_log("a.vert", "0(3) : error C1008: undefined variable\n"),
            "a.vert:3: error C1008: undefined variable\n");
  EXPECT_EQ(gl::format_shader_log("a.vert", "something odd\n"), "a.vert: something odd\n");
}

}  // namespace
}  // namespace bounce
