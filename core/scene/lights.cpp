#include "scene/lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/directions.h"

namespace bounce {

namespace {

// The smooth edge needs the cones apart; glTF's sample code keeps them
// 0.001 apart in the cosine too.
double edge_width(const punctual_light& l) {
  return std::max(1e-3, std::cos(l.inner_cone) - std::cos(l.outer_cone));
}

}  // namespace

double cone_share(const punctual_light& l, const vec3& from_light) {
  if (l.type != light_type::spot) return 1.0;
  const double c = glm::dot(l.direction, from_light);
  const double t = std::clamp((c - std::cos(l.outer_cone)) / edge_width(l), 0.0, 1.0);
  return t * t;
}

light_arrival light_at(const punctual_light& l, const vec3& p, double far) {
  light_arrival a;
  if (l.type == light_type::sun) {
    a.to_light = -l.direction;
    a.shadow_end = p + far * a.to_light;
    a.irradiance = l.intensity;
    return a;
  }
  const vec3 to = l.position - p;
  const double r2 = glm::dot(to, to);
  if (!(r2 > 0.0)) return a;  // at the light: no direction, no light
  a.to_light = to / std::sqrt(r2);
  a.shadow_end = l.position;
  a.irradiance = l.intensity * (cone_share(l, -a.to_light) / r2);
  return a;
}

double cone_solid_angle(const punctual_light& l) {
  if (l.type != light_type::spot) return 4.0 * std::numbers::pi;
  // In the cosine c: share t^2 over the edge [co, co + w], then 1 up to
  // c = 1. The edge is cut short where co + w passes 1 (cones under 2.6
  // degrees, or closer than the 1e-3 the width is held to).
  const double co = std::cos(l.outer_cone);
  const double w = edge_width(l);
  const double a = std::min(w, std::max(0.0, 1.0 - co));
  return 2.0 * std::numbers::pi * (a * a * a / (3.0 * w * w) + std::max(0.0, 1.0 - co - w));
}

rgb emitted_power(const punctual_light& l, double scene_radius) {
  if (l.type == light_type::sun) return l.intensity * (std::numbers::pi * scene_radius * scene_radius);
  return l.intensity * cone_solid_angle(l);
}

light_photon sample_light_photon(const punctual_light& l, const vec3& scene_centre, double scene_radius, double u1,
                                 double u2) {
  light_photon out;
  switch (l.type) {
    case light_type::point:
      out.origin = l.position;
      out.direction = sphere_direction(u1, u2);
      break;
    case light_type::spot: {
      const double co = std::cos(l.outer_cone);
      out.origin = l.position;
      out.direction = cone_direction(l.direction, co, u1, u2);
      out.weight = cone_share(l, out.direction) * 2.0 * std::numbers::pi * (1.0 - co) / cone_solid_angle(l);
      break;
    }
    case light_type::sun: {
      vec3 t, b;
      orthonormal_basis(l.direction, t, b);
      // Uniform on the disc (polar, area-preserving), a little upstream.
      const double r = scene_radius * std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
      out.origin = scene_centre - 1.01 * scene_radius * l.direction + r * std::cos(phi) * t + r * std::sin(phi) * b;
      out.direction = l.direction;
      break;
    }
  }
  return out;
}

const char* light_type_name(light_type t) {
  switch (t) {
    case light_type::point:
      return "point";
    case light_type::spot:
      return "spot";
    case light_type::sun:
      return "sun";
  }
  return "point";
}

}  // namespace bounce
