#include "measure/exact_solutions.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include "measure/closed_forms.h"
#include "radiosity/solver.h"

namespace bounce {
namespace {

using std::numbers::pi;

// Emitting polygons of the scene: (corners, exitance).
std::vector<std::pair<std::vector<vec3>, rgb>> emitting_polygons(const scene& s) {
  std::vector<std::pair<std::vector<vec3>, rgb>> out;
  for (const surface& surf : s.surfaces) {
    const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    if (!mesh) continue;
    for (const polygon_face& f : mesh->faces) {
      const rgb ke = s.materials[f.material].ke;
      if (channel_sum(ke) <= 0.0) continue;
      std::vector<vec3> corners;
      for (int i : f.position) corners.push_back(mesh->positions[i]);
      out.emplace_back(std::move(corners), pi * ke);
    }
  }
  return out;
}

double area_of(std::span<const vec3> polygon) {
  vec3 sum(0.0);
  for (std::size_t i = 0; i < polygon.size(); ++i) sum += glm::cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * glm::length(sum);
}

vec3 normal_of(std::span<const vec3> polygon) {
  return glm::normalize(glm::cross(polygon[1] - polygon[0], polygon[2] - polygon[0]));
}

}  // namespace

std::vector<rgb> exact_vertex_radiosity(exact_kind kind, const scene& s, const patch_mesh& mesh) {
  std::vector<rgb> exact(mesh.vertex_count(), rgb(0.0));
  switch (kind) {
    case exact_kind::none:
      break;
    case exact_kind::furnace:
      for (std::size_t v = 0; v < exact.size(); ++v)
        exact[v] = mesh.vertex_emission[v] / (rgb(1.0) - mesh.vertex_rho[v]);
      break;
    case exact_kind::sphere_interior: {
      rgb emitted(0.0);
      for (std::size_t e = 0; e < mesh.element_count(); ++e)
        emitted += mesh.vertex_emission[mesh.elements[e][0]] * mesh.element_areas[e];
      const double area = total_area(mesh);
      for (std::size_t v = 0; v < exact.size(); ++v) {
        const rgb rho = mesh.vertex_rho[v];
        exact[v] = mesh.vertex_emission[v] + rho * emitted / ((rgb(1.0) - rho) * area);
      }
      break;
    }
    case exact_kind::emitter_receiver: {
      // At the receive point: the one-sided limit on a shared edge, where
      // the function is continuous but the polygon touches the point.
      const auto emitters = emitting_polygons(s);
      for (std::size_t v = 0; v < exact.size(); ++v) {
        rgb received(0.0);
        for (const auto& [corners, exitance] : emitters)
          received += exitance * point_polygon_form_factor(mesh.receive_points[v], mesh.normals[v], corners);
        exact[v] = mesh.vertex_emission[v] + mesh.vertex_rho[v] * received;
      }
      break;
    }
  }
  return exact;
}

rgb exact_reflected_power(exact_kind kind, const scene& s, const patch_mesh& mesh) {
  if (kind == exact_kind::furnace || kind == exact_kind::sphere_interior) {
    // The closed form is constant over every element: its integral is exact.
    return reflected_power(mesh, exact_vertex_radiosity(kind, s, mesh));
  }
  if (kind != exact_kind::emitter_receiver) return rgb(not_measured);
  // One emitting rectangle and one receiving rectangle, opposed or at
  // 90 degrees along a shared edge: power = rho E A_emitter F(emitter -> receiver).
  const auto emitters = emitting_polygons(s);
  std::optional<std::vector<vec3>> receiver;
  rgb rho(0.0);
  for (const surface& surf : s.surfaces) {
    const auto* m = std::get_if<polygon_mesh>(&surf.geometry);
    if (!m || m->faces.size() != 1 || channel_sum(s.materials[m->faces[0].material].rho) <= 0.0) continue;
    receiver.emplace();
    for (int i : m->faces[0].position) receiver->push_back(m->positions[i]);
    rho = s.materials[m->faces[0].material].rho;
  }
  if (emitters.size() != 1 || !receiver || receiver->size() != 4 || emitters[0].first.size() != 4)
    return rgb(not_measured);
  const auto& [emitter, exitance] = emitters[0];
  const double a = glm::length(emitter[1] - emitter[0]), b = glm::length(emitter[2] - emitter[1]);
  const vec3 ne = normal_of(emitter), nr = normal_of(*receiver);
  double f = not_measured;
  if (glm::dot(ne, nr) < -0.999) {
    f = parallel_rectangles(a, b, std::abs(glm::dot(nr, emitter[0] - (*receiver)[0])));
  } else if (std::abs(glm::dot(ne, nr)) < 1e-3) {
    // The shared edge is the emitter's edge lying in the receiver's plane.
    for (int i = 0; i < 4; ++i) {
      const vec3 p = emitter[i], q = emitter[(i + 1) % 4];
      if (std::abs(glm::dot(nr, p - (*receiver)[0])) < 1e-9 && std::abs(glm::dot(nr, q - (*receiver)[0])) < 1e-9) {
        const double l = glm::length(q - p);
        const double w = area_of(emitter) / l, h = area_of(*receiver) / l;
        f = perpendicular_rectangles(l, w, h);
      }
    }
  }
  return rho * exitance * area_of(emitter) * f;
}

rgb reflected_power(const patch_mesh& mesh, std::span<const rgb> radiosity) {
  rgb total(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    rgb mean(0.0);
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.elements[e][i];
      mean += radiosity[v] - mesh.vertex_emission[v];
    }
    total += mean * (mesh.element_areas[e] / 3.0);
  }
  return total;
}

vertex_error vertex_relative_error(std::span<const rgb> test, std::span<const rgb> exact) {
  if (test.size() != exact.size()) return {not_measured, not_measured};
  double largest = 0.0, sum = 0.0;
  for (const rgb& c : exact) {
    largest = std::max({largest, std::abs(c.r), std::abs(c.g), std::abs(c.b)});
    sum += std::abs(c.r) + std::abs(c.g) + std::abs(c.b);
  }
  const double floor = 1e-6 * largest;
  const double mean = sum / (3.0 * double(std::max<std::size_t>(exact.size(), 1)));
  vertex_error e;
  double squares = 0.0;
  for (std::size_t v = 0; v < test.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      const double d = test[v][c] - exact[v][c];
      squares += d * d;
      e.max = std::max(e.max, std::abs(d) / std::max(std::abs(exact[v][c]), floor));
    }
  if (!(mean > 0.0)) return {not_measured, not_measured};
  e.rmse = std::sqrt(squares / (3.0 * double(test.size()))) / mean;
  return e;
}

}  // namespace bounce
