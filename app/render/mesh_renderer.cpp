#include "mesh_renderer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glad/gl.h>

#include "gl_program.h"
#include "shader_files.h"

namespace bounce::gl {

mesh_renderer::~mesh_renderer() {
  // The context may already be gone when a renderer outlives it; the
  // owner destroys the renderer first (see headless and viewer).
  if (vao_) glDeleteVertexArrays(1, &vao_);
  const unsigned int buffers[] = {static_buffer_, dynamic_buffer_, index_buffer_};
  for (unsigned int b : buffers)
    if (b) glDeleteBuffers(1, &b);
  if (program_) glDeleteProgram(program_);
  if (wire_program_) glDeleteProgram(wire_program_);
}

bool mesh_renderer::init(std::string& error) {
  const shader_source vertex = shader_file("gouraud.vert");
  program_ = make_program(vertex, shader_file("gouraud.frag"), error);
  if (!program_) return false;
  wire_program_ = make_program(vertex, shader_file("wire.frag"), error);
  if (!wire_program_) return false;
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &static_buffer_);
  glGenBuffers(1, &dynamic_buffer_);
  glGenBuffers(1, &index_buffer_);
  return true;
}

mesh_arrays make_mesh_arrays(const patch_mesh& mesh) {
  mesh_arrays out;
  const std::size_t vertex_count = mesh.vertex_count();
  out.vertex_count = vertex_count;
  // Element size seen from a vertex: the square root of its elements' mean area.
  std::vector<double> area_sum(vertex_count, 0.0);
  std::vector<int> count(vertex_count, 0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      area_sum[mesh.elements[e][k]] += mesh.element_areas[e];
      ++count[mesh.elements[e][k]];
    }
  // Static: position, normal, reflectance, element size, interleaved.
  std::vector<float>& data = out.vertices;
  data.reserve(vertex_count * 10);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.positions[v][k]));
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.normals[v][k]));
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.vertex_rho[v][k]));
    const float size = count[v] ? float(std::sqrt(area_sum[v] / count[v])) : 0.0f;
    data.push_back(size);
    out.largest_element = std::max(out.largest_element, size);
  }
  out.indices.reserve(mesh.element_count() * 3);
  for (const glm::ivec3& t : mesh.elements)
    for (int k = 0; k < 3; ++k) out.indices.push_back(unsigned(t[k]));
  return out;
}

void mesh_renderer::upload(const mesh_arrays& arrays) {
  vertex_count_ = arrays.vertex_count;
  largest_element_ = arrays.largest_element;
  const std::vector<float>& data = arrays.vertices;
  const std::vector<unsigned int>& indices = arrays.indices;
  index_count_ = int(indices.size());

  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, static_buffer_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
  const GLsizei stride = 10 * sizeof(float);
  for (GLuint attribute = 0; attribute < 3; ++attribute) {
    glEnableVertexAttribArray(attribute);
    glVertexAttribPointer(attribute, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(std::uintptr_t(attribute * 3 * sizeof(float))));
  }
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 1, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(std::uintptr_t(9 * sizeof(float))));
  // Dynamic: radiosity then unshot, two blocks, rewritten every step.
  glBindBuffer(GL_ARRAY_BUFFER, dynamic_buffer_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertex_count_ * 6 * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glEnableVertexAttribArray(4);
  glVertexAttribPointer(4, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float),
                        reinterpret_cast<const void*>(std::uintptr_t(vertex_count_ * 3 * sizeof(float))));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index_buffer_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(unsigned int)), indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
}

std::vector<glm::vec3> solution_colours(const radiosity_snapshot& snapshot) {
  // The solution stays in double up to here; GL takes float.
  const std::size_t n = snapshot.radiosity.size();
  std::vector<glm::vec3> colours(2 * n);
  for (std::size_t v = 0; v < n; ++v) {
    colours[v] = glm::vec3(snapshot.radiosity[v]);
    colours[n + v] = glm::vec3(snapshot.unshot_vertex[v]);
  }
  return colours;
}

void mesh_renderer::update(const std::vector<glm::vec3>& colours, const glm::vec3& ambient) {
  if (colours.size() != 2 * vertex_count_) return;  // a solution of another mesh: nothing to show
  glBindBuffer(GL_ARRAY_BUFFER, dynamic_buffer_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(colours.size() * sizeof(glm::vec3)), colours.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  ambient_ = ambient;
}

void mesh_renderer::draw(const glm::mat4& view_projection, const glm::vec3& eye,
                         const display_settings& settings) const {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // rooms are seen from inside; back faces are shown (or highlighted)
  glBindVertexArray(vao_);
  glUseProgram(program_);
  glUniformMatrix4fv(glGetUniformLocation(program_, "view_projection"), 1, GL_FALSE, &view_projection[0][0]);
  const glm::vec3 ambient = settings.ambient ? ambient_ : glm::vec3(0.0f);
  glUniform3fv(glGetUniformLocation(program_, "ambient"), 1, &ambient[0]);
  glUniform3fv(glGetUniformLocation(program_, "eye"), 1, &eye[0]);
  glUniform1f(glGetUniformLocation(program_, "exposure"), float(settings.exposure));
  glUniform1i(glGetUniformLocation(program_, "tone_curve"), int(settings.curve));
  glUniform1i(glGetUniformLocation(program_, "false_colour"), int(settings.colours));
  glUniform1f(glGetUniformLocation(program_, "largest_element"), std::max(largest_element_, 1e-30f));
  glUniform1i(glGetUniformLocation(program_, "highlight_back_faces"), settings.highlight_back_faces ? 1 : 0);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  if (settings.wireframe) {
    // Edges pulled slightly towards the eye so they win the depth test.
    glUseProgram(wire_program_);
    glUniformMatrix4fv(glGetUniformLocation(wire_program_, "view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    glUniform4f(glGetUniformLocation(wire_program_, "colour"), 0.0f, 0.0f, 0.0f, 1.0f);
    glEnable(GL_POLYGON_OFFSET_LINE);
    glPolygonOffset(-1.0f, -1.0f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_POLYGON_OFFSET_LINE);
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace bounce::gl
