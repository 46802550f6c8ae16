#include "radiosity/solver_settings.h"

#include <algorithm>

#include "radiosity/solver.h"
#include "scene/scene_info.h"

namespace bounce {

mesher_params mesher_params_for(const solver_settings& settings, const scene& s) {
  mesher_params p;
  p.shadow_outlines = settings.shadow_outlines;
  if (settings.adaptive.enabled) {
    // Adaptive meshing starts coarser and lets elements shoot, so that the
    // shooters refine with the receivers (docs/radiosity.md).
    p.max_edge = settings.max_edge > 0.0 ? settings.max_edge : adaptive_start_edge(s);
    p.patch_edge = settings.patch_edge < 0.0 ? 0.0 : settings.patch_edge;
    p.a_priori_min_edge = settings.min_edge > 0.0 ? settings.min_edge : default_min_edge(p.max_edge);
    return p;
  }
  if (settings.method == solver_method::hierarchical) {
    // The elements are the hierarchy's finest level, and are split where
    // links need them: they start at the uniform default.
    p.max_edge = settings.max_edge > 0.0 ? settings.max_edge : hierarchical_max_edge(s);
    p.patch_edge = 0.0;
    p.solver_min_edge = settings.min_edge;
    return p;
  }
  p.max_edge = settings.max_edge > 0.0 ? settings.max_edge : default_max_edge(s);
  // Patches of about 16 elements shoot by default: on the Cornell box much
  // faster to converge than element shooting, for a small deviation
  // (docs/radiosity.md).
  p.patch_edge = settings.patch_edge < 0.0 ? 4.0 * p.max_edge : settings.patch_edge;
  return p;
}

radiosity_params radiosity_params_for(const solver_settings& settings) {
  radiosity_params p;
  p.method = settings.method;
  p.form_factors = settings.form_factors;
  p.adaptive = settings.adaptive;
  p.adaptive.min_edge = settings.min_edge;
  p.hierarchical.tolerance = settings.link_tolerance;
  p.hierarchical.split_elements = true;
  p.hierarchical.min_edge = settings.min_edge;
  // Each tolerance is solved to the run's stopping point, or 2%, before
  // the links are refined further.
  p.hierarchical.refine_below = std::max(settings.stop.remaining, 0.02);
  p.view = settings.view;
  return p;
}

namespace {
constexpr solver_method_name solver_names[] = {
    {solver_method::hierarchical, "hierarchical"},
    {solver_method::progressive, "progressive"},
};
}  // namespace

std::span<const solver_method_name> solver_method_names() {
  return solver_names;
}

std::string_view name_of(solver_method method) {
  for (const auto& m : solver_names)
    if (m.method == method) return m.name;
  return "unknown";
}

std::optional<solver_method> solver_method_named(std::string_view name) {
  for (const auto& m : solver_names)
    if (m.name == name) return m.method;
  return std::nullopt;
}

namespace {
constexpr form_factor_method_name method_names[] = {
    {form_factor_method::raycast, "raycast"},
    {form_factor_method::hemicube, "hemicube"},
};
}  // namespace

std::span<const form_factor_method_name> form_factor_method_names() {
  return method_names;
}

std::string_view name_of(form_factor_method method) {
  for (const auto& m : method_names)
    if (m.method == method) return m.name;
  return "unknown";
}

std::optional<form_factor_method> form_factor_method_named(std::string_view name) {
  for (const auto& m : method_names)
    if (m.name == name) return m.method;
  return std::nullopt;
}

}  // namespace bounce
