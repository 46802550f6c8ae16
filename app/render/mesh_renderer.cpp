#include "mesh_renderer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <glad/gl.h>
#include <glm/matrix.hpp>

#include "gl_program.h"
#include "scene/texture.h"
#include "shader_files.h"

namespace bounce::gl {
namespace {

// Halves an RGB image (2x2 boxes; an odd last row or column counts once),
// for images past the driver's largest texture.
void halve(int& width, int& height, std::vector<float>& texels) {
  const int w = std::max(1, width / 2), h = std::max(1, height / 2);
  std::vector<float> out(std::size_t(w) * h * 3, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0.0f;
        int n = 0;
        for (int j = 2 * y; j < std::min(height, 2 * y + 2); ++j)
          for (int i = 2 * x; i < std::min(width, 2 * x + 2); ++i, ++n)
            sum += texels[(std::size_t(j) * width + i) * 3 + c];
        out[(std::size_t(y) * w + x) * 3 + c] = sum / float(n);
      }
  width = w;
  height = h;
  texels = std::move(out);
}

// The shader with `name` defined after its #version line; #line keeps the
// compiler's line numbers those of the file.
shader_source with_define(shader_source source, const std::string& name) {
  const std::size_t end = source.text.find('\n');
  if (end != std::string::npos) source.text.insert(end + 1, "#define " + name + "\n#line 2\n");
  return source;
}

}  // namespace

mesh_renderer::~mesh_renderer() {
  // The context may already be gone when a renderer outlives it; the
  // owner destroys the renderer first (see headless and viewer).
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
  delete_textures();
  const unsigned int buffers[] = {static_buffer_, dynamic_buffer_, index_buffer_};
  for (unsigned int b : buffers)
    if (b) glDeleteBuffers(1, &b);
  if (program_) glDeleteProgram(program_);
  if (wire_program_) glDeleteProgram(wire_program_);
  if (textured_program_) glDeleteProgram(textured_program_);
  if (background_program_) glDeleteProgram(background_program_);
}

bool mesh_renderer::init(std::string& error) {
  const shader_source vertex = shader_file("gouraud.vert");
  const shader_source fragment = shader_file("gouraud.frag");
  program_ = make_program(vertex, fragment, error);
  if (!program_) return false;
  textured_program_ = make_program(with_define(vertex, "TEXTURED"), with_define(fragment, "TEXTURED"), error);
  if (!textured_program_) return false;
  background_program_ = make_program(with_define(vertex, "BACKGROUND"), with_define(fragment, "BACKGROUND"), error);
  if (!background_program_) return false;
  wire_program_ = make_program(vertex, shader_file("wire.frag"), error);
  if (!wire_program_) return false;
  glGenVertexArrays(1, &vao_);
  glGenVertexArrays(1, &empty_vao_);  // the background's full-screen triangle needs no attributes
  glGenBuffers(1, &static_buffer_);
  glGenBuffers(1, &dynamic_buffer_);
  glGenBuffers(1, &index_buffer_);
  return true;
}

mesh_arrays make_mesh_arrays(const patch_mesh& mesh, std::shared_ptr<const scene> source) {
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
  auto has_back = [&](std::size_t v) {
    if (!source || v >= mesh.vertex_surfaces.size()) return false;
    const int surf = mesh.vertex_surfaces[v];
    if (surf < 0 || std::size_t(surf) >= source->surfaces.size()) return false;
    const surface& s = source->surfaces[std::size_t(surf)];
    return s.back_side >= 0 || s.back_of >= 0;
  };
  // Static: position, normal, reflectance, element size (its sign: has_back), uv, interleaved.
  const bool has_uvs = mesh.uvs.size() == vertex_count;
  std::vector<float>& data = out.vertices;
  data.reserve(vertex_count * mesh_arrays::floats_per_vertex);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.positions[v][k]));
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.normals[v][k]));
    for (int k = 0; k < 3; ++k) data.push_back(float(mesh.vertex_rho[v][k]));
    const float size = count[v] ? float(std::sqrt(area_sum[v] / count[v])) : 0.0f;
    // Negative on surfaces with a back (two-sided): the shader draws only their front.
    data.push_back(has_back(v) ? -size : size);
    out.largest_element = std::max(out.largest_element, size);
    for (int k = 0; k < 2; ++k) data.push_back(has_uvs ? float(mesh.uvs[v][k]) : 0.0f);
  }
  // Untextured elements in the mesh's order (one draw, as before textures),
  // then each textured material's elements (a draw each, its texture bound).
  auto texture_of = [&](int material) {
    if (!source || material < 0 || std::size_t(material) >= source->materials.size()) return -1;
    const int t = source->materials[std::size_t(material)].texture;
    return t >= 0 && std::size_t(t) < source->textures.size() ? t : -1;
  };
  const bool has_materials = mesh.element_materials.size() == mesh.element_count();
  std::map<int, std::vector<std::size_t>> textured;  // material -> its elements
  out.indices.reserve(mesh.element_count() * 3);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int material = has_materials ? mesh.element_materials[e] : -1;
    if (texture_of(material) >= 0) {
      textured[material].push_back(e);
      continue;
    }
    for (int k = 0; k < 3; ++k) out.indices.push_back(unsigned(mesh.elements[e][k]));
  }
  out.untextured_count = out.indices.size();
  for (const auto& [material, elements] : textured) {
    textured_run run;
    run.texture = texture_of(material);
    run.emitted = glm::vec3(source->materials[std::size_t(material)].ke);
    run.first = out.indices.size();
    for (std::size_t e : elements)
      for (int k = 0; k < 3; ++k) out.indices.push_back(unsigned(mesh.elements[e][k]));
    run.count = out.indices.size() - run.first;
    out.textured.push_back(run);
  }
  out.source = std::move(source);
  return out;
}

void mesh_renderer::delete_textures() {
  for (const gl_texture& t : textures_)
    if (t.id) glDeleteTextures(1, &t.id);
  textures_.clear();
  textures_source_.reset();
}

void mesh_renderer::upload_textures(const std::shared_ptr<const scene>& source) {
  background_ = source ? glm::vec3(source->background) : glm::vec3(0.0f);
  sky_ = source && source->sky.on();
  if (sky_) {
    zenith_ = glm::vec3(source->sky.zenith);
    horizon_ = glm::vec3(source->sky.horizon);
    sky_up_ = glm::vec3(glm::normalize(source->sky.up));
  }
  if (source == textures_source_) return;
  delete_textures();
  textures_source_ = source;
  if (!source) return;
  GLint largest = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  for (const texture& t : source->textures) {
    gl_texture g;
    g.kind = t.kind;
    g.color0 = glm::vec3(t.color0);
    g.color1 = glm::vec3(t.color1);
    g.scale = float(t.scale);
    // The mean of the scene's own texels, as the mesher and the ray tracer take it.
    const rgb mean = texture_mean(t);
    for (int c = 0; c < 3; ++c) g.inverse_mean[c] = mean[c] > 0.0 ? float(1.0 / mean[c]) : 0.0f;
    if (t.kind == texture_kind::image && t.width > 0 && t.height > 0 &&
        t.texels.size() == std::size_t(t.width) * t.height * 3) {
      int width = t.width, height = t.height;
      std::vector<float> reduced;
      const float* texels = t.texels.data();
      if (largest > 0 && std::max(width, height) > largest) {
        reduced = t.texels;
        while (std::max(width, height) > largest) halve(width, height, reduced);
        texels = reduced.data();
      }
      // Half float: linear values kept as they are (above 1 too), to
      // 0.05%; sampled bilinearly with repeat, as texture_value does.
      glGenTextures(1, &g.id);
      glBindTexture(GL_TEXTURE_2D, g.id);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, width, height, 0, GL_RGB, GL_FLOAT, texels);
      glGenerateMipmap(GL_TEXTURE_2D);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glBindTexture(GL_TEXTURE_2D, 0);
    } else if (t.kind == texture_kind::image) {
      g.kind = texture_kind::checker;  // no texels: texture_value's 1 everywhere
      g.color0 = g.color1 = glm::vec3(1.0f);
      g.inverse_mean = glm::vec3(1.0f);
    }
    textures_.push_back(g);
  }
}

void mesh_renderer::upload(const mesh_arrays& arrays) {
  vertex_count_ = arrays.vertex_count;
  largest_element_ = arrays.largest_element;
  untextured_count_ = arrays.untextured_count;
  textured_ = arrays.textured;
  upload_textures(arrays.source);
  const std::vector<float>& data = arrays.vertices;
  const std::vector<unsigned int>& indices = arrays.indices;
  index_count_ = int(indices.size());

  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, static_buffer_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(data.size() * sizeof(float)), data.data(), GL_STATIC_DRAW);
  const GLsizei stride = mesh_arrays::floats_per_vertex * sizeof(float);
  for (GLuint attribute = 0; attribute < 3; ++attribute) {
    glEnableVertexAttribArray(attribute);
    glVertexAttribPointer(attribute, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<const void*>(std::uintptr_t(attribute * 3 * sizeof(float))));
  }
  glEnableVertexAttribArray(5);
  glVertexAttribPointer(5, 1, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(std::uintptr_t(9 * sizeof(float))));
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(6, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<const void*>(std::uintptr_t(10 * sizeof(float))));
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
  const glm::vec3 ambient = settings.ambient ? ambient_ : glm::vec3(0.0f);
  // The uniforms both variants of gouraud.frag share.
  auto use = [&](unsigned int program) {
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    glUniform3fv(glGetUniformLocation(program, "ambient"), 1, &ambient[0]);
    glUniform3fv(glGetUniformLocation(program, "eye"), 1, &eye[0]);
    glUniform1f(glGetUniformLocation(program, "exposure"), float(settings.exposure));
    glUniform1i(glGetUniformLocation(program, "tone_curve"), int(settings.curve));
    glUniform1i(glGetUniformLocation(program, "false_colour"), int(settings.colours));
    glUniform1f(glGetUniformLocation(program, "largest_element"), std::max(largest_element_, 1e-30f));
    glUniform1i(glGetUniformLocation(program, "highlight_back_faces"), settings.highlight_back_faces ? 1 : 0);
  };
  use(program_);
  glDrawElements(GL_TRIANGLES, GLsizei(untextured_count_), GL_UNSIGNED_INT, nullptr);
  if (!textured_.empty()) {
    const unsigned int p = textured_program_;
    use(p);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(p, "image"), 0);
    const GLint mode = glGetUniformLocation(p, "texture_mode"), emitted = glGetUniformLocation(p, "emitted"),
                inverse_mean = glGetUniformLocation(p, "inverse_mean"), checker0 = glGetUniformLocation(p, "checker0"),
                checker1 = glGetUniformLocation(p, "checker1"), scale = glGetUniformLocation(p, "checker_scale");
    for (const textured_run& run : textured_) {
      if (run.texture < 0 || std::size_t(run.texture) >= textures_.size()) continue;
      const gl_texture& t = textures_[std::size_t(run.texture)];
      glUniform1i(mode, t.id ? 1 : 2);
      glBindTexture(GL_TEXTURE_2D, t.id);
      glUniform3fv(emitted, 1, &run.emitted[0]);
      glUniform3fv(inverse_mean, 1, &t.inverse_mean[0]);
      glUniform3fv(checker0, 1, &t.color0[0]);
      glUniform3fv(checker1, 1, &t.color1[0]);
      glUniform1f(scale, t.scale);
      glDrawElements(GL_TRIANGLES, GLsizei(run.count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(std::uintptr_t(run.first * sizeof(unsigned int))));
    }
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  // The background where no sample holds a surface: a full-screen triangle
  // at the far plane through the same shader, so it gets the surfaces'
  // exposure and tone curve (and in linear output, its radiance unscaled).
  // Black needs no pass: the callers clear to black. False colours keep it.
  if (settings.colours == false_colour::none && (sky_ || background_ != glm::vec3(0.0f))) {
    const unsigned int p = background_program_;
    use(p);
    glUniform3fv(glGetUniformLocation(p, "background"), 1, &background_[0]);
    glUniform1i(glGetUniformLocation(p, "sky"), sky_ ? 1 : 0);
    glUniform3fv(glGetUniformLocation(p, "zenith"), 1, &zenith_[0]);
    glUniform3fv(glGetUniformLocation(p, "horizon"), 1, &horizon_[0]);
    glUniform3fv(glGetUniformLocation(p, "sky_up"), 1, &sky_up_[0]);
    const glm::mat4 inverse = glm::inverse(view_projection);
    glUniformMatrix4fv(glGetUniformLocation(p, "inverse_view_projection"), 1, GL_FALSE, &inverse[0][0]);
    GLint viewport[4] = {0, 0, 1, 1};
    glGetIntegerv(GL_VIEWPORT, viewport);
    glUniform4f(glGetUniformLocation(p, "viewport"), float(viewport[0]), float(viewport[1]), float(viewport[2]),
                float(viewport[3]));
    glBindVertexArray(empty_vao_);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glBindVertexArray(vao_);
  }
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
