#include "render/mesh_renderer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glad/gl.h>
#include <glm/matrix.hpp>

#include "render/gl_program.h"
#include "render/shader_files.h"
#include "scene/texture.h"

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
  for (const program_set& set : programs_)
    for (const unsigned int program : {set.plain, set.textured, set.mirror, set.glass})
      if (program) glDeleteProgram(program);
  if (wire_program_) glDeleteProgram(wire_program_);
  if (background_program_) glDeleteProgram(background_program_);
}

bool mesh_renderer::init(std::string& error) {
  const shader_source vertex = shader_file("gouraud.vert");
  const shader_source fragment = shader_file("gouraud.frag");
  for (const bool multisampled : {false, true}) {
    // Each variant of gouraud.vert/.frag (see there) for a framebuffer with
    // and without multisampling.
    auto build = [&](std::initializer_list<const char*> defines) {
      shader_source v = vertex, f = fragment;
      if (!multisampled) {
        v = with_define(v, "SINGLE_SAMPLE");
        f = with_define(f, "SINGLE_SAMPLE");
      }
      for (const char* name : defines) {
        v = with_define(v, name);
        f = with_define(f, name);
      }
      return make_program(v, f, error);
    };
    program_set& set = programs_[multisampled ? 1 : 0];
    if (!(set.plain = build({}))) return false;
    if (!(set.textured = build({"TEXTURED"}))) return false;
    if (!(set.mirror = build({"TEXTURED", "SPECULAR"}))) return false;
    if (!(set.glass = build({"TEXTURED", "SPECULAR", "GLASS"}))) return false;
  }
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
      if (reduced.empty() && t.alpha.size() == std::size_t(width) * std::size_t(height)) {
        // With its coverage, for cut-outs (a texture halved to fit loses it).
        std::vector<float> rgba(t.alpha.size() * 4);
        for (std::size_t k = 0; k < t.alpha.size(); ++k) {
          for (int c = 0; c < 3; ++c) rgba[4 * k + std::size_t(c)] = texels[3 * k + std::size_t(c)];
          rgba[4 * k + 3] = t.alpha[k];
        }
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, width, height, 0, GL_RGBA, GL_FLOAT, rgba.data());
      } else {
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB16F, width, height, 0, GL_RGB, GL_FLOAT, texels);
      }
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
  solution_vertex_count_ = arrays.solution_vertex_count;
  blends_ = arrays.blends;
  largest_element_ = arrays.largest_element;
  plain_count_ = arrays.plain_count;
  plain_chunks_ = arrays.plain_chunks;
  outline_first_ = arrays.outline_first;
  outline_count_ = arrays.indices.size() - arrays.outline_first;
  runs_ = arrays.runs;
  // A refined mesh of the same scene keeps its specular surfaces: their
  // cube maps keep showing the scene (refreshed in turn); new ones start
  // black and get a first round at once.
  const bool same_probes =
      arrays.probes.size() == probe_surfaces_.size() &&
      std::equal(arrays.probes.begin(), arrays.probes.end(), probe_surfaces_.begin(),
                 [](const specular_surface& a, const specular_surface& b) { return a.centre == b.centre; });
  probe_surfaces_ = arrays.probes;
  bounds_min_ = arrays.bounds_min;
  bounds_max_ = arrays.bounds_max;
  // 128 texels a face: a mirror sphere filling a quarter of the view shows
  // its surroundings at about the view's resolution.
  probes_.resize(probe_surfaces_.size(), 128);
  stale_faces_ = 2 * 6 * probe_surfaces_.size();
  if (!same_probes) {
    urgent_faces_ = 6 * probe_surfaces_.size();
    next_face_ = 0;
  }
  upload_textures(arrays.source);
  const std::vector<float>& data = arrays.vertices;
  const std::vector<unsigned int>& indices = arrays.indices;

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
  // Dynamic: radiosity then remaining, two blocks, rewritten every step.
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

void mesh_renderer::update(const std::vector<glm::vec3>& colours, const glm::vec3& ambient) {
  const std::size_t n = solution_vertex_count_;
  if (colours.size() != 2 * n) return;  // a solution of another mesh: nothing to show
  const std::vector<glm::vec3>* shown = &colours;
  if (vertex_count_ > n) {
    // The finer display of curved surfaces: its extra vertices blend the solution's.
    const std::size_t extra = vertex_count_ - n;
    expanded_.resize(2 * vertex_count_);
    for (int block = 0; block < 2; ++block) {
      const glm::vec3* in = colours.data() + block * n;
      glm::vec3* out = expanded_.data() + block * vertex_count_;
      std::copy(in, in + n, out);
      for (std::size_t x = 0; x < extra; ++x) {
        const vertex_blend& b = blends_[x];
        out[n + x] = b.wa * in[b.a] + b.wb * in[b.b] + b.wc * in[b.c];
      }
    }
    shown = &expanded_;
  }
  glBindBuffer(GL_ARRAY_BUFFER, dynamic_buffer_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(shown->size() * sizeof(glm::vec3)), shown->data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  ambient_ = ambient;
  stale_faces_ = 2 * 6 * probe_surfaces_.size();
}

bool mesh_renderer::refresh_reflections(std::size_t max_faces, double headlight) {
  if (probe_surfaces_.empty()) return false;
  const std::size_t faces = 6 * probe_surfaces_.size();
  if ((headlight > 0.0) != probes_headlit_) {  // the preview ends (or starts): the probes show another scene
    probes_headlit_ = headlight > 0.0;
    urgent_faces_ = faces;
    stale_faces_ = std::max(stale_faces_, 2 * faces);
  }
  if (stale_faces_ == 0) return false;
  const float diagonal = std::max(glm::length(bounds_max_ - bounds_min_), 1e-6f);
  display_settings linear;  // what the probes hold: radiance, unscaled
  linear.curve = tone_curve::linear;
  linear.headlight = headlight;
  for (std::size_t done = 0; (done < max_faces || urgent_faces_ > 0) && stale_faces_ > 0; ++done, --stale_faces_) {
    // The cursor goes on round the faces across updates, so that a solver
    // that updates every few frames still has every face refreshed in turn.
    const std::size_t next = next_face_++ % faces;
    const std::size_t probe = next / 6;
    const glm::vec3 centre = probe_surfaces_[probe].centre;
    probes_.render_face(
        probe, int(next % 6), centre, 1e-4f * diagonal, 4.0f * diagonal,
        [&](const glm::mat4& view_projection) { draw_scene(view_projection, centre, linear, int(probe)); });
    if (urgent_faces_ > 0) --urgent_faces_;
  }
  return stale_faces_ > 0;
}

void mesh_renderer::draw_scene(const glm::mat4& view_projection, const glm::vec3& eye, const display_settings& settings,
                               int hidden) const {
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // rooms are seen from inside; back faces are shown (or highlighted)
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  const program_set& set = programs_[samples > 1 ? 1 : 0];
  glBindVertexArray(vao_);
  const glm::vec3 ambient = settings.ambient ? ambient_ : glm::vec3(0.0f);
  // The uniforms every variant of gouraud.frag shares.
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
    glUniform1f(glGetUniformLocation(program, "headlight"), float(settings.headlight));
  };
  // Mirrors and glass first: they stand in front of walls more often than
  // behind them, and what they hide then fails the depth test before its
  // fragment shader runs (llvmpipe shades on the CPU; every pixel counts).
  // Glass has a program of its own, so that mirrors skip refraction.
  enum class pass { glass, mirror, textured };
  auto pass_of = [&](const material_run& run) {
    if (run.probe < 0) return pass::textured;
    const glm::vec3 kt = probe_surfaces_[std::size_t(run.probe)].kt;
    return glm::any(glm::greaterThan(kt, glm::vec3(0.0f))) ? pass::glass : pass::mirror;
  };
  for (const pass group : {pass::glass, pass::mirror, pass::textured}) {
    const bool specular = group != pass::textured;
    const unsigned int p = group == pass::glass ? set.glass : group == pass::mirror ? set.mirror : set.textured;
    bool used = false;
    for (const material_run& run : runs_) {
      if (pass_of(run) != group || (specular && run.probe == hidden)) continue;
      if (!used) {
        use(p);
        glUniform1i(glGetUniformLocation(p, "image"), 0);
        if (specular) {
          glUniform1i(glGetUniformLocation(p, "environment"), 1);
          glUniform3fv(glGetUniformLocation(p, "scene_min"), 1, &bounds_min_[0]);
          glUniform3fv(glGetUniformLocation(p, "scene_max"), 1, &bounds_max_[0]);
          // The first four point lights (the Whitted scenes have one or two).
          std::vector<glm::vec4> positions;
          std::vector<glm::vec3> intensities, axes;
          std::vector<glm::vec2> cones;
          if (textures_source_)
            for (const punctual_light& light : textures_source_->lights) {
              if (positions.size() == 4) break;
              const bool sun = light.type == light_type::sun;
              positions.emplace_back(sun ? glm::vec3(-light.direction) : glm::vec3(light.position), sun ? 0.0f : 1.0f);
              intensities.emplace_back(light.intensity);
              axes.emplace_back(light.direction);
              // Points and suns: a cone wider than every direction.
              const double outer = std::cos(light.outer_cone), inner = std::cos(light.inner_cone);
              cones.push_back(light.type == light_type::spot
                                  ? glm::vec2(float(outer), float(1.0 / std::max(1e-3, inner - outer)))
                                  : glm::vec2(-2.0f, 1.0f));
            }
          glUniform1i(glGetUniformLocation(p, "light_count"), GLint(positions.size()));
          if (!positions.empty()) {
            const auto n = GLsizei(positions.size());
            glUniform4fv(glGetUniformLocation(p, "light_position"), n, &positions[0][0]);
            glUniform3fv(glGetUniformLocation(p, "light_intensity"), n, &intensities[0][0]);
            glUniform3fv(glGetUniformLocation(p, "light_axis"), n, &axes[0][0]);
            glUniform2fv(glGetUniformLocation(p, "light_cone"), n, &cones[0][0]);
          }
        }
        used = true;
      }
      glActiveTexture(GL_TEXTURE0);
      if (run.texture >= 0 && std::size_t(run.texture) < textures_.size()) {
        const gl_texture& t = textures_[std::size_t(run.texture)];
        glUniform1i(glGetUniformLocation(p, "texture_mode"), t.id ? 1 : 2);
        glBindTexture(GL_TEXTURE_2D, t.id);
        glUniform3fv(glGetUniformLocation(p, "inverse_mean"), 1, &t.inverse_mean[0]);
        glUniform3fv(glGetUniformLocation(p, "checker0"), 1, &t.color0[0]);
        glUniform3fv(glGetUniformLocation(p, "checker1"), 1, &t.color1[0]);
        glUniform1f(glGetUniformLocation(p, "checker_scale"), t.scale);
      } else {
        glUniform1i(glGetUniformLocation(p, "texture_mode"), 0);
        glBindTexture(GL_TEXTURE_2D, 0);
      }
      glUniform3fv(glGetUniformLocation(p, "emitted"), 1, &run.emitted[0]);
      if (group == pass::textured) {
        const bool glows = run.emission_texture >= 0 && std::size_t(run.emission_texture) < textures_.size() &&
                           textures_[std::size_t(run.emission_texture)].id;
        glUniform1i(glGetUniformLocation(p, "emission_mode"), glows ? 1 : 0);
        glUniform1f(glGetUniformLocation(p, "alpha"), run.alpha);
        glUniform1f(glGetUniformLocation(p, "alpha_cutoff"), run.alpha_cutoff);
        if (glows) {
          const gl_texture& t = textures_[std::size_t(run.emission_texture)];
          glActiveTexture(GL_TEXTURE2);
          glBindTexture(GL_TEXTURE_2D, t.id);
          glUniform1i(glGetUniformLocation(p, "emission_image"), 2);
          glUniform3fv(glGetUniformLocation(p, "emission_inverse_mean"), 1, &t.inverse_mean[0]);
          glActiveTexture(GL_TEXTURE0);
        }
      }
      if (specular) {
        const specular_surface& probe = probe_surfaces_[std::size_t(run.probe)];
        // A solid seen from outside: its far half is hidden by its near half.
        if (probe.solid && glm::distance(eye, probe.centre) > probe.radius)
          glEnable(GL_CULL_FACE);
        else
          glDisable(GL_CULL_FACE);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_CUBE_MAP, probes_.texture(std::size_t(run.probe)));
        glUniform3fv(glGetUniformLocation(p, "probe_centre"), 1, &probe.centre[0]);
        glUniform1f(glGetUniformLocation(p, "probe_radius"), probe.radius);
        glUniform1i(glGetUniformLocation(p, "probe_thin"), probe.thin ? 1 : 0);
        glUniform3fv(glGetUniformLocation(p, "mirror_weight"), 1, &probe.kr[0]);
        glUniform3fv(glGetUniformLocation(p, "transmit_weight"), 1, &probe.kt[0]);
        glUniform1f(glGetUniformLocation(p, "ior"), probe.ior);
        glUniform1i(glGetUniformLocation(p, "fresnel_on"), probe.fresnel ? 1 : 0);
        glUniform3fv(glGetUniformLocation(p, "specular_colour"), 1, &probe.specular[0]);
        glUniform1f(glGetUniformLocation(p, "shininess"), probe.shininess);
      }
      glDrawElements(GL_TRIANGLES, GLsizei(run.count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(std::uintptr_t(run.first * sizeof(unsigned int))));
    }
  }
  glDisable(GL_CULL_FACE);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);
  use(set.plain);
  // Only the chunks in the view: llvmpipe's frame time follows the triangles sent.
  for (const auto& [first, count] : visible_ranges(plain_chunks_, view_projection))
    glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::uintptr_t(first * sizeof(unsigned int))));
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
    // Edges pulled slightly towards the eye so they win the depth test (wire.frag).
    glUseProgram(wire_program_);
    glUniformMatrix4fv(glGetUniformLocation(wire_program_, "view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    glUniform4f(glGetUniformLocation(wire_program_, "colour"), 0.0f, 0.0f, 0.0f, 1.0f);
    glDrawElements(GL_LINES, GLsizei(outline_count_), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(std::uintptr_t(outline_first_ * sizeof(unsigned int))));
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace bounce::gl
