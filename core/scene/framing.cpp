#include "scene/framing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce {

bounds3 scene_bounds(const scene& s) {
  bounds3 b{vec3(std::numeric_limits<double>::infinity()), vec3(-std::numeric_limits<double>::infinity())};
  auto grow = [&](const vec3& p) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  };
  for (const surface& surf : s.surfaces) {
    std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, polygon_mesh>) {
            for (const polygon_face& f : g.faces)
              for (int i : f.position) grow(g.positions[i]);
          } else if constexpr (std::is_same_v<T, sphere>) {
            grow(g.center - vec3(g.radius));
            grow(g.center + vec3(g.radius));
          } else if constexpr (std::is_same_v<T, quadric>) {
            grow(g.box_min);
            grow(g.box_max);
          } else if constexpr (std::is_same_v<T, bezier_surface>) {
            for (const auto& patch : g.patches)
              for (const vec3& p : patch) grow(p);
          } else {
            for (const vec3& p : g.control) grow(p);
          }
        },
        surf.geometry);
  }
  if (b.min.x > b.max.x) b = {vec3(0.0), vec3(0.0)};
  return b;
}

camera fit_camera(const scene& s) {
  bounds3 b = scene_bounds(s);
  vec3 center = 0.5 * (b.min + b.max);
  double radius = std::max(0.5 * glm::length(b.max - b.min), 1e-12);

  // Look from the horizontal side (+-x, +-z) with the largest net
  // projected polygon area facing it (front-facing minus back-facing: a wall
  // seen from behind hides what is in front of it). For a room open on one
  // side that is the opening; a closed object nets zero everywhere and is
  // seen from +z, the OpenGL convention.
  // The Newell vector of a planar polygon is twice its area times its normal,
  // so summing them gives every side's net projected area at once.
  vec3 net(0.0);
  double total = 0.0;
  for (const surface& surf : s.surfaces) {
    if (auto* mesh = std::get_if<polygon_mesh>(&surf.geometry)) {
      for (const polygon_face& f : mesh->faces) {
        vec3 newell(0.0);
        for (std::size_t i = 0; i < f.position.size(); ++i)
          newell +=
              glm::cross(mesh->positions[f.position[i]], mesh->positions[f.position[(i + 1) % f.position.size()]]);
        net += 0.5 * newell;
        total += 0.5 * glm::length(newell);
      }
    }
  }
  const vec3 sides[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}};
  vec3 from = sides[0];
  double best = 1e-6 * total;  // below this, round-off of a closed surface
  for (const vec3& side : sides) {
    if (glm::dot(net, side) > best) {
      best = glm::dot(net, side);
      from = side;
    }
  }
  camera cam;
  cam.fov_y_degrees = 45.0;
  double distance = radius / std::sin(glm::radians(cam.fov_y_degrees) * 0.5);
  cam.target = center;
  cam.eye = center + from * distance;
  cam.up = vec3(0, 1, 0);
  return cam;
}

}  // namespace bounce
