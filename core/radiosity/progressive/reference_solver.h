// The full-matrix reference solver for small scenes: the exact solution of
// the same discrete system the progressive solver converges to,
//   (I - R K) B = E + L,   K = F M,
// with F(v, e) from the same form-factor method, M the vertex-to-element
// mean, R = diag(rho_v) and L the point lights' direct radiosity. Solved
// directly (LU with partial pivoting, Eigen) and by Gauss-Seidel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

// The dense matrix is vertices^2 doubles: 6000 vertices is 288 MB.
inline constexpr std::size_t max_reference_vertices = 6000;

struct reference_params {
  form_factor_params form_factors;
  int max_gauss_seidel_iterations = 10000;
  double gauss_seidel_tolerance = 1e-13;  // stop when the largest change is below this x the largest B
};

struct reference_solution {
  std::vector<rgb> radiosity;  // LU
  std::vector<rgb> radiosity_gauss_seidel;
  double residual = 0.0;               // LU: max |(I - R K) B - b| / max |b|
  double residual_gauss_seidel = 0.0;  // the same for Gauss-Seidel
  int gauss_seidel_iterations = 0;
  std::uint64_t rays = 0;
  double seconds_matrix = 0.0, seconds_lu = 0.0, seconds_gauss_seidel = 0.0;
};

// Returns false with `error` set when the mesh is too large for a dense matrix.
bool solve_reference(const scene& s, const patch_mesh& mesh, const reference_params& params, reference_solution& out,
                     std::string& error);

}  // namespace bounce
