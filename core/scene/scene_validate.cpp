#include "scene/scene_validate.h"

// validate_scene: the rules every scene obeys, whether loaded or built in
// code. Each message names the object at fault.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

namespace bounce {
namespace {

// Coordinates beyond this are absurd for any scene unit and would lose all
// precision in the offsets the ray tracer and form factors need.
constexpr double max_coordinate = 1e12;
constexpr int max_image_side = 16384;
// Emitted radiance above this is a mistake in any unit system, and with
// coordinates up to max_coordinate keeps pi * ke * area finite.
constexpr double max_emission = 1e9;

bool finite(const vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool in_range(const vec3& v) {
  return finite(v) && glm::all(glm::lessThanEqual(glm::abs(v), vec3(max_coordinate)));
}

// %g style, so that huge values stay short (DBL_MAX is 1.79769e+308).
std::string str(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string str(const vec3& v) {
  return "(" + str(v.x) + ", " + str(v.y) + ", " + str(v.z) + ")";
}

std::string check_material(const material& m) {
  const std::string who = "material '" + m.name + "': ";
  const std::pair<const char*, const rgb*> colours[] = {
      {"rho", &m.rho}, {"ke", &m.ke}, {"kr", &m.kr}, {"kt", &m.kt}, {"specular", &m.specular}};
  for (auto [name, c] : colours)
    if (!finite(*c)) return who + name + " " + str(*c) + " is not finite";
  for (int i = 0; i < 3; ++i) {
    if (m.rho[i] < 0.0 || m.rho[i] >= 1.0)
      return who + "rho " + str(m.rho) + " must be in [0, 1) per channel (rho >= 1 creates energy)";
    if (m.ke[i] < 0.0) return who + "emission ke " + str(m.ke) + " must not be negative";
    if (m.ke[i] > max_emission) return who + "emission ke " + str(m.ke) + " is above the limit of " + str(max_emission);
    if (m.kr[i] < 0.0 || m.kr[i] > 1.0) return who + "kr " + str(m.kr) + " must be in [0, 1]";
    if (m.kt[i] < 0.0 || m.kt[i] > 1.0) return who + "kt " + str(m.kt) + " must be in [0, 1]";
    if (m.specular[i] < 0.0) return who + "specular " + str(m.specular) + " must not be negative";
    if (m.rho[i] + m.kr[i] + m.kt[i] > 1.0 + 1e-9)
      return who + "rho + kr + kt exceeds 1 in channel " + std::to_string(i) + " (reflects more than it receives)";
  }
  if (!std::isfinite(m.ior) || m.ior <= 0.0) return who + "ior must be a positive number";
  if (!std::isfinite(m.shininess) || m.shininess < 0.0) return who + "shininess must be >= 0";
  return {};
}

std::string check_surface(const scene& s, const surface& surf) {
  // The caller names the scene file; name the surface's own file only when
  // it is another one (an OBJ the scene includes).
  const bool other_file = !surf.source.empty() && surf.source != s.source;
  const std::string who = (other_file ? surf.source + ": " : "") + "surface '" + surf.name + "': ";
  auto material_ok = [&](int m) { return m >= 0 && m < static_cast<int>(s.materials.size()); };
  return std::visit(
      [&](const auto& g) -> std::string {
        using T = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<T, polygon_mesh>) {
          for (const vec3& p : g.positions)
            if (!in_range(p)) return who + "vertex " + str(p) + " is not finite or absurdly large";
          for (const vec3& n : g.normals)
            if (!finite(n)) return who + "normal is not finite";
          for (const polygon_face& f : g.faces) {
            if (!material_ok(f.material)) return who + "face without a valid material";
            for (int i : f.position)
              if (i < 0 || i >= static_cast<int>(g.positions.size())) return who + "vertex index out of range";
            for (int i : f.normal)
              if (i < 0 || i >= static_cast<int>(g.normals.size())) return who + "normal index out of range";
            for (int i : f.uv)
              if (i < 0 || i >= static_cast<int>(g.uvs.size())) return who + "uv index out of range";
          }
        } else if constexpr (std::is_same_v<T, sphere>) {
          if (!material_ok(g.material)) return who + "invalid material";
          if (!in_range(g.center)) return who + "centre is not finite";
          if (!(g.radius > 0.0) || g.radius > max_coordinate) return who + "radius must be positive and finite";
        } else if constexpr (std::is_same_v<T, quadric>) {
          if (!material_ok(g.material)) return who + "invalid material";
          const double c[] = {g.a, g.b, g.c, g.d, g.e, g.f, g.g, g.h, g.j, g.k};
          bool any_variable = false;
          for (int i = 0; i < 10; ++i) {
            if (!std::isfinite(c[i])) return who + "coefficients must be finite";
            if (i < 9 && c[i] != 0.0) any_variable = true;
          }
          if (!any_variable) return who + "all coefficients but k are zero: no surface";
          if (!in_range(g.box_min) || !in_range(g.box_max)) return who + "box is not finite";
          if (!glm::all(glm::lessThan(g.box_min, g.box_max))) return who + "box min must be below max on every axis";
        } else if constexpr (std::is_same_v<T, bezier_surface>) {
          if (!material_ok(g.material)) return who + "invalid material";
          if (g.patches.empty()) return who + "no patches";
          for (const auto& patch : g.patches)
            for (const vec3& p : patch)
              if (!in_range(p)) return who + "control point " + str(p) + " is not finite";
        } else {
          if (!material_ok(g.material)) return who + "invalid material";
          if (g.rows < 4 || g.cols < 4) return who + "a bicubic B-spline needs at least 4x4 control points";
          if (g.control.size() != static_cast<std::size_t>(g.rows) * g.cols) return who + "control grid size mismatch";
          for (const vec3& p : g.control)
            if (!in_range(p)) return who + "control point " + str(p) + " is not finite";
        }
        return {};
      },
      surf.geometry);
}

bool has_emission(const material& m) {
  return m.ke.r > 0.0 || m.ke.g > 0.0 || m.ke.b > 0.0;
}

// True when some surface uses an emitting material (with `lamps_only`,
// one whose glow is not a texture's).
bool has_emitting_surface(const scene& s, bool lamps_only = false) {
  auto lamp = [&](const material& m) { return has_emission(m) && !(lamps_only && m.emission_texture >= 0); };
  for (const surface& surf : s.surfaces) {
    bool emits = std::visit(
        [&](const auto& g) {
          using T = std::decay_t<decltype(g)>;
          if constexpr (std::is_same_v<T, polygon_mesh>) {
            for (const polygon_face& f : g.faces)
              if (lamp(s.materials[f.material])) return true;
            return false;
          } else {
            return lamp(s.materials[g.material]);
          }
        },
        surf.geometry);
    if (emits) return true;
  }
  return false;
}

}  // namespace

std::string check_camera(const camera& c) {
  if (!in_range(c.eye) || !in_range(c.target) || !finite(c.up)) return "camera: eye, target and up must be finite";
  vec3 forward = c.target - c.eye;
  if (glm::length(forward) == 0.0) return "camera: eye and target are the same point";
  if (glm::length(c.up) == 0.0) return "camera: up is zero";
  if (glm::length(glm::cross(glm::normalize(forward), glm::normalize(c.up))) < 1e-6)
    return "camera: up is parallel to the view direction";
  if (!(c.fov_y_degrees >= min_fov_degrees && c.fov_y_degrees <= max_fov_degrees))
    return "camera: fov must be from 0.001 to 179 degrees";
  if (c.width < 1 || c.height < 1 || c.width > max_image_side || c.height > max_image_side)
    return "camera: size " + std::to_string(c.width) + "x" + std::to_string(c.height) + " must be from 1 to " +
           std::to_string(max_image_side) + " per side";
  return {};
}

std::string validate_scene(const scene& s) {
  for (const material& m : s.materials) {
    if (std::string e = check_material(m); !e.empty()) return e;
    for (const int t : {m.texture, m.emission_texture})
      if (t < -1 || t >= int(s.textures.size()))
        return "material '" + m.name + "': texture " + std::to_string(t) + " does not exist";
  }
  if (s.surfaces.empty()) return "no surfaces";
  for (const surface& surf : s.surfaces)
    if (std::string e = check_surface(s, surf); !e.empty()) return e;
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const punctual_light& l = s.lights[i];
    std::string who = "lights[" + std::to_string(i) + "]: ";
    if (!in_range(l.position)) return who + "position is not finite";
    if (!finite(l.intensity) || glm::any(glm::lessThan(l.intensity, vec3(0.0))))
      return who + "intensity must be finite and >= 0";
    if (l.type != light_type::point && !(in_range(l.direction) && std::abs(glm::length(l.direction) - 1.0) < 1e-6))
      return who + "direction must be a finite unit vector";
    if (l.type == light_type::spot &&
        !(l.inner_cone >= 0.0 && l.inner_cone < l.outer_cone && l.outer_cone <= 0.5 * std::numbers::pi))
      return who + "spot cones need 0 <= inner < outer <= 90 degrees";
  }
  if (!finite(s.background) || glm::any(glm::lessThan(s.background, vec3(0.0))))
    return "background must be finite and >= 0";
  for (const rgb& c : {s.sky.zenith, s.sky.horizon})
    if (!finite(c) || glm::any(glm::lessThan(c, vec3(0.0)))) return "sky: radiance must be finite and >= 0";
  if (!in_range(s.sky.up) || !(glm::length(s.sky.up) > 0.0)) return "sky.up must be a finite, non-zero direction";
  for (const texture& t : s.textures) {
    // A texture scales rho, so its values stay in [0, 1] like a reflectance.
    auto unit = [](const rgb& c) {
      return finite(c) && glm::all(glm::greaterThanEqual(c, rgb(0.0))) && glm::all(glm::lessThanEqual(c, rgb(1.0)));
    };
    if (t.kind == texture_kind::checker &&
        (!(t.scale > 0.0) || !std::isfinite(t.scale) || !unit(t.color0) || !unit(t.color1)))
      return "texture '" + t.name + "': checker needs colours in [0, 1] and a positive scale";
  }
  if (std::string e = check_camera(s.view); !e.empty()) return e;
  return {};
}

bool has_lamp(const scene& s) {
  if (s.sky.on()) return true;
  for (const punctual_light& l : s.lights)
    if (any_positive(l.intensity)) return true;
  return has_emitting_surface(s, /*lamps_only=*/true);
}

bool has_light_source(const scene& s) {
  if (s.sky.on()) return true;
  for (const punctual_light& l : s.lights)
    if (glm::any(glm::greaterThan(l.intensity, vec3(0.0)))) return true;
  return has_emitting_surface(s);
}

}  // namespace bounce
