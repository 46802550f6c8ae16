// What the hierarchical solver's tests share: its parameters, solving to
// a residual, the Cornell box and a comparison of solutions.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "radiosity/solver.h"

namespace bounce::test_support {

inline radiosity_params hierarchical(double tolerance) {
  radiosity_params p;
  p.method = solver_method::hierarchical;
  p.hierarchical.tolerance = tolerance;
  return p;
}

// With elements split where links need them, not below min_edge.
inline radiosity_params splitting(double tolerance, double min_edge) {
  radiosity_params p = hierarchical(tolerance);
  p.hierarchical.split_elements = true;
  p.hierarchical.min_edge = min_edge;
  return p;
}

// Steps until the discretisation is final and the residual is below `fraction`.
inline void solve(radiosity_solver& solver, double fraction, int max_steps = 400) {
  for (int i = 0; i < max_steps; ++i) {
    if (solver.stats.remaining_final && solver.stats.remaining <= fraction) return;
    if (!step_solver(solver)) return;
  }
  ADD_FAILURE() << "not converged in " << max_steps << " steps: residual " << solver.stats.remaining;
}

inline scene cornell() {
  return default_cornell_box();
}

// The integral over the mesh of per-vertex values, interpolated linearly
// over each element as the Gouraud view shows them.
inline rgb integral_over_elements(const patch_mesh& mesh, const std::vector<rgb>& per_vertex) {
  rgb sum(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) sum += per_vertex[std::size_t(mesh.elements[e][k])] * (mesh.element_areas[e] / 3.0);
  return sum;
}

// The largest difference of any channel, relative to b's largest channel.
inline double largest_relative_difference(const std::vector<rgb>& a, const std::vector<rgb>& b) {
  double largest = 0.0, scale = 0.0;
  for (const rgb& x : b) scale = std::max({scale, x.r, x.g, x.b});
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(a[i][c] - b[i][c]) / scale);
  return largest;
}

// Whether a floor point lies outside the Cornell box's short block's
// footprint (the official data's corners) but within 30 mm of it: its
// contact shadow.
inline bool near_short_block(const vec3& p) {
  const vec2 corners[4] = {{130, 65}, {82, 225}, {240, 272}, {290, 114}};
  const vec2 q(p.x, p.z);
  double nearest = INFINITY;
  int inside = 0;
  for (int k = 0; k < 4; ++k) {
    const vec2 a = corners[k], b = corners[(k + 1) % 4];
    const double t = std::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
    nearest = std::min(nearest, glm::length(q - (a + t * (b - a))));
    const vec2 edge = b - a, to = q - a;
    inside += edge.x * to.y - edge.y * to.x > 0.0 ? 1 : -1;
  }
  return std::abs(inside) != 4 && nearest < 30.0;
}

}  // namespace bounce::test_support
