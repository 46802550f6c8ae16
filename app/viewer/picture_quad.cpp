#include "viewer/picture_quad.h"

#include <glad/gl.h>

#include "render/gl_program.h"

namespace bounce {
namespace {

// The triangle (-1,-1), (3,-1), (-1,3) covers the viewport; row 0 of the
// picture is its top.
const char* const vertex_shader = R"(#version 330 core
out vec2 uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  uv = vec2(p.x, 1.0 - p.y);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const fragment_shader = R"(#version 330 core
in vec2 uv;
uniform sampler2D picture;
out vec4 colour;
void main() { colour = vec4(texture(picture, uv).rgb, 1.0); }
)";

}  // namespace

picture_quad::~picture_quad() {
  if (texture_) glDeleteTextures(1, &texture_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (program_) glDeleteProgram(program_);
}

bool picture_quad::init(std::string& error) {
  program_ = gl::make_program({"picture_quad.vert", vertex_shader}, {"picture_quad.frag", fragment_shader}, error);
  if (!program_) return false;
  glGenVertexArrays(1, &vao_);
  return true;
}

void upload_srgb_texture(unsigned& texture, const image& picture, double exposure) {
  if (!texture) glGenTextures(1, &texture);
  const std::vector<unsigned char> rows = to_srgb_rows(picture, exposure);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, picture.width, picture.height, 0, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void picture_quad::upload(const image& picture, double exposure) {
  upload_srgb_texture(texture_, picture, exposure);
  width_ = picture.width;
  height_ = picture.height;
}

void picture_quad::draw() const {
  if (!has_picture()) return;
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glUniform1i(glGetUniformLocation(program_, "picture"), 0);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace bounce
