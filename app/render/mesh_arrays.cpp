#include "render/mesh_arrays.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>
#include <glm/vector_relational.hpp>

#include "render/closed_surface.h"

namespace bounce::gl {
namespace {

// 30 bits of a Morton (Z-order) code: 10 per axis of the point's place in the box.
std::uint32_t morton_code(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& size) {
  auto spread = [](std::uint32_t v) {  // 10 bits to every third of 30
    v = (v | (v << 16)) & 0x030000FFu;
    v = (v | (v << 8)) & 0x0300F00Fu;
    v = (v | (v << 4)) & 0x030C30C3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
  };
  std::uint32_t code = 0;
  for (int a = 0; a < 3; ++a) {
    const float t = size[a] > 0.0f ? (p[a] - lo[a]) / size[a] : 0.0f;
    code |= spread(std::uint32_t(std::clamp(t, 0.0f, 1.0f) * 1023.0f)) << a;
  }
  return code;
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> visible_ranges(const std::vector<draw_chunk>& chunks,
                                                                const glm::mat4& view_projection) {
  // The frustum's planes from the matrix's rows (Gribb and Hartmann):
  // w + x, w - x, w + y, w - y, w + z, w - z >= 0 inside.
  glm::vec4 planes[6];
  const glm::mat4& m = view_projection;
  const glm::vec4 row[4] = {{m[0][0], m[1][0], m[2][0], m[3][0]},
                            {m[0][1], m[1][1], m[2][1], m[3][1]},
                            {m[0][2], m[1][2], m[2][2], m[3][2]},
                            {m[0][3], m[1][3], m[2][3], m[3][3]}};
  for (int a = 0; a < 3; ++a) {
    planes[2 * a] = row[3] + row[a];
    planes[2 * a + 1] = row[3] - row[a];
  }
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const draw_chunk& c : chunks) {
    bool inside = true;
    for (const glm::vec4& plane : planes) {
      // The box's corner farthest along the plane's normal.
      const glm::vec3 far(plane.x > 0.0f ? c.hi.x : c.lo.x, plane.y > 0.0f ? c.hi.y : c.lo.y,
                          plane.z > 0.0f ? c.hi.z : c.lo.z);
      if (glm::dot(glm::vec3(plane), far) + plane.w < 0.0f) {
        inside = false;
        break;
      }
    }
    if (!inside) continue;
    if (!out.empty() && out.back().first + out.back().second == c.first)
      out.back().second += c.count;
    else
      out.emplace_back(c.first, c.count);
  }
  return out;
}

mesh_arrays make_mesh_arrays(const patch_mesh& mesh, std::shared_ptr<const scene> source) {
  mesh_arrays out;
  const std::size_t solution_count = mesh.vertex_count();
  // Curved surfaces drawn finer, within twice the mesh's triangles (at
  // least 30,000): llvmpipe's frame time follows the triangle count.
  const curved_display curved = make_curved_display(mesh, source.get(), display_degrees_per_step,
                                                    std::max<std::size_t>(2 * mesh.element_count(), 30000));
  const std::size_t vertex_count = solution_count + curved.positions.size();
  out.vertex_count = vertex_count;
  out.solution_vertex_count = solution_count;
  out.blends = curved.blends;
  // Element size seen from a vertex: the square root of its elements' mean area.
  std::vector<double> area_sum(solution_count, 0.0);
  std::vector<int> count(solution_count, 0);
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
  const bool has_uvs = mesh.uvs.size() == solution_count;
  std::vector<float>& data = out.vertices;
  data.reserve(vertex_count * mesh_arrays::floats_per_vertex);
  auto push = [&data](const auto& value, int n) {
    for (int k = 0; k < n; ++k) data.push_back(float(value[k]));
  };
  std::vector<float> sizes(solution_count);
  for (std::size_t v = 0; v < solution_count; ++v) {
    push(mesh.positions[v], 3);
    push(mesh.normals[v], 3);
    push(mesh.vertex_rho[v], 3);
    const float size = count[v] ? float(std::sqrt(area_sum[v] / count[v])) : 0.0f;
    // Negative on surfaces with a back (two-sided): the shader draws only their front.
    sizes[v] = has_back(v) ? -size : size;
    data.push_back(sizes[v]);
    out.largest_element = std::max(out.largest_element, size);
    push(has_uvs ? glm::vec2(mesh.uvs[v]) : glm::vec2(0.0f), 2);
  }
  for (std::size_t x = 0; x < curved.positions.size(); ++x) {
    const vertex_blend& b = curved.blends[x];
    auto blend = [&](const auto& values) {
      return double(b.wa) * values[b.a] + double(b.wb) * values[b.b] + double(b.wc) * values[b.c];
    };
    push(curved.positions[x], 3);
    push(curved.normals[x], 3);
    push(blend(mesh.vertex_rho), 3);
    data.push_back(b.wa * sizes[b.a] + b.wb * sizes[b.b] + b.wc * sizes[b.c]);
    push(has_uvs ? glm::vec2(blend(mesh.uvs)) : glm::vec2(0.0f), 2);
  }
  out.bounds_min = glm::vec3(std::numeric_limits<float>::max());
  out.bounds_max = glm::vec3(-std::numeric_limits<float>::max());
  for (const vec3& p : mesh.positions) {
    out.bounds_min = glm::min(out.bounds_min, glm::vec3(p));
    out.bounds_max = glm::max(out.bounds_max, glm::vec3(p));
  }
  if (solution_count == 0) out.bounds_min = out.bounds_max = glm::vec3(0.0f);

  // Plain elements in the mesh's order (one draw), then a run for each
  // textured material and each specular surface (a draw each, with its
  // texture or its reflection probe bound).
  const bool has_materials = mesh.element_materials.size() == mesh.element_count();
  const bool has_surfaces = mesh.element_surfaces.size() == mesh.element_count();
  auto material_of = [&](std::size_t e) -> const material* {
    const int m = has_materials ? mesh.element_materials[e] : -1;
    return source && m >= 0 && std::size_t(m) < source->materials.size() ? &source->materials[std::size_t(m)] : nullptr;
  };
  auto texture_of = [&](const material* m) {
    return m && m->texture >= 0 && std::size_t(m->texture) < source->textures.size() ? m->texture : -1;
  };
  auto emission_of = [&](const material* m) {
    return m && m->emission_texture >= 0 && std::size_t(m->emission_texture) < source->textures.size()
               ? m->emission_texture
               : -1;
  };
  auto specular = [](const material* m) { return m && glm::any(glm::greaterThan(glm::max(m->kr, m->kt), rgb(0.0))); };
  // (material, surface if specular else -1) -> its elements
  std::map<std::pair<int, int>, std::vector<std::size_t>> runs;
  std::vector<glm::vec3> display_positions;  // for the specular surfaces' closed_surface test
  auto emit = [&](std::size_t e) {
    for (std::size_t t = 3 * curved.first[e]; t < 3 * curved.first[e + 1]; ++t)
      out.indices.push_back(curved.triangles[t]);
  };
  out.indices.reserve(curved.triangles.size());
  std::vector<std::pair<std::uint32_t, std::size_t>> plain;  // (Morton code of the centre, element)
  const glm::vec3 box_size = out.bounds_max - out.bounds_min;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const material* m = material_of(e);
    if (texture_of(m) < 0 && emission_of(m) < 0 && !specular(m)) {
      plain.emplace_back(morton_code(glm::vec3(element_centroid(mesh, e)), out.bounds_min, box_size), e);
      continue;
    }
    const int surface = specular(m) && has_surfaces ? mesh.element_surfaces[e] : -1;
    runs[{mesh.element_materials[e], surface}].push_back(e);
  }
  std::sort(plain.begin(), plain.end());
  draw_chunk chunk;
  auto close_chunk = [&] {
    chunk.count = out.indices.size() - chunk.first;
    if (chunk.count == 0) return;
    chunk.lo = glm::vec3(std::numeric_limits<float>::max());
    chunk.hi = glm::vec3(-std::numeric_limits<float>::max());
    for (std::size_t i = chunk.first; i < out.indices.size(); ++i) {
      const float* p = &data[std::size_t(out.indices[i]) * mesh_arrays::floats_per_vertex];
      chunk.lo = glm::min(chunk.lo, glm::vec3(p[0], p[1], p[2]));
      chunk.hi = glm::max(chunk.hi, glm::vec3(p[0], p[1], p[2]));
    }
    out.plain_chunks.push_back(chunk);
    chunk = draw_chunk{};
    chunk.first = out.indices.size();
  };
  for (const auto& [code, e] : plain) {
    emit(e);
    if (out.indices.size() - chunk.first >= 3 * chunk_triangles) close_chunk();
  }
  close_chunk();
  out.plain_count = out.indices.size();
  for (const auto& [key, elements] : runs) {
    const material& m = source->materials[std::size_t(key.first)];
    material_run run;
    run.texture = texture_of(&m);
    run.emission_texture = emission_of(&m);
    run.alpha = float(m.alpha);
    run.alpha_cutoff = float(m.alpha_cutoff);
    run.emitted = glm::vec3(m.ke);
    run.first = out.indices.size();
    for (std::size_t e : elements) emit(e);
    run.count = out.indices.size() - run.first;
    if (specular(&m)) {
      specular_surface probe;
      probe.surface = key.second;
      probe.kr = glm::vec3(m.kr);
      probe.kt = glm::vec3(m.kt);
      probe.ior = float(m.ior);
      probe.fresnel = m.fresnel;
      probe.specular = glm::vec3(m.specular);
      probe.shininess = float(m.shininess);
      glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
      for (std::size_t i = run.first; i < out.indices.size(); ++i) {
        const float* p = &data[std::size_t(out.indices[i]) * mesh_arrays::floats_per_vertex];
        lo = glm::min(lo, glm::vec3(p[0], p[1], p[2]));
        hi = glm::max(hi, glm::vec3(p[0], p[1], p[2]));
      }
      probe.centre = 0.5f * (lo + hi);
      for (std::size_t i = run.first; i < out.indices.size(); ++i) {
        const float* p = &data[std::size_t(out.indices[i]) * mesh_arrays::floats_per_vertex];
        probe.radius = std::max(probe.radius, glm::length(glm::vec3(p[0], p[1], p[2]) - probe.centre));
      }
      // A sheet: thinner than a twentieth of its extent (a pane, a flat mirror).
      const glm::vec3 extent = hi - lo;
      probe.thin = std::min({extent.x, extent.y, extent.z}) <= 0.05f * std::max({extent.x, extent.y, extent.z});
      if (display_positions.empty()) {
        display_positions.resize(vertex_count);
        for (std::size_t v = 0; v < vertex_count; ++v) {
          const float* p = &data[v * mesh_arrays::floats_per_vertex];
          display_positions[v] = glm::vec3(p[0], p[1], p[2]);
        }
      }
      probe.solid = bounds_solid_outward(out.indices, run.first, run.count, display_positions);
      run.probe = int(out.probes.size());
      out.probes.push_back(probe);
    }
    out.runs.push_back(run);
  }
  out.outline_first = out.indices.size();
  out.indices.insert(out.indices.end(), curved.outline.begin(), curved.outline.end());
  out.source = std::move(source);
  return out;
}

std::vector<glm::vec3> solution_colours(const radiosity_snapshot& snapshot) {
  // The solution stays in double up to here; GL takes float.
  const std::size_t n = snapshot.radiosity.size();
  std::vector<glm::vec3> colours(2 * n);
  for (std::size_t v = 0; v < n; ++v) {
    colours[v] = glm::vec3(snapshot.radiosity[v]);
    colours[n + v] = glm::vec3(snapshot.remaining[v]);
  }
  return colours;
}

}  // namespace bounce::gl
