#include "radiosity/progressive/reference_solver.h"

#include <chrono>
#include <cmath>

#include <Eigen/Dense>

#include "radiosity/transfer/point_lights.h"

namespace bounce {
namespace {

// Row-major: Gauss-Seidel walks rows.
using matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t) {
  return std::chrono::duration<double>(clock_type::now() - t).count();
}

// max |(I - rho K) x - b| / max |b| for one channel.
double relative_residual(const matrix& k, const Eigen::VectorXd& rho, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b) {
  const Eigen::VectorXd r = x - rho.cwiseProduct(k * x) - b;
  const double scale = b.cwiseAbs().maxCoeff();
  return scale > 0.0 ? r.cwiseAbs().maxCoeff() / scale : r.cwiseAbs().maxCoeff();
}

}  // namespace

bool solve_reference(const scene& s, const patch_mesh& mesh, const reference_params& params, reference_solution& out,
                     std::string& error) {
  const std::size_t n = mesh.vertex_count();
  if (n > max_reference_vertices) {
    error = "the reference solver takes at most " + std::to_string(max_reference_vertices) +
            " vertices; this mesh has " + std::to_string(n) + " (use a larger --max-edge)";
    return false;
  }
  out = {};
  auto start = clock_type::now();
  form_factor_context context = make_form_factor_context(mesh, params.form_factors);

  // K = F M, one shooter (column block) at a time.
  matrix k = matrix::Zero(Eigen::Index(n), Eigen::Index(n));
  std::vector<double> column(n);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    out.rays += form_factors_to_element(context, int(e), column);
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Index u = mesh.elements[e][corner];
      for (std::size_t v = 0; v < n; ++v) k(Eigen::Index(v), u) += column[v] / 3.0;
    }
  }
  const std::vector<rgb> lights = point_light_radiosity(s, mesh, context, out.rays);
  out.seconds_matrix = since(start);

  out.radiosity.assign(n, rgb(0.0));
  out.radiosity_gauss_seidel.assign(n, rgb(0.0));
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd rho(static_cast<Eigen::Index>(n)), b(static_cast<Eigen::Index>(n));
    for (std::size_t v = 0; v < n; ++v) {
      rho[Eigen::Index(v)] = mesh.vertex_rho[v][c];
      b[Eigen::Index(v)] = mesh.vertex_emission[v][c] + lights[v][c];
    }
    // Direct: LU with partial pivoting.
    start = clock_type::now();
    matrix a = -(rho.asDiagonal() * k);
    a.diagonal().array() += 1.0;
    const Eigen::VectorXd x = a.partialPivLu().solve(b);
    out.seconds_lu += since(start);
    out.residual = std::max(out.residual, relative_residual(k, rho, x, b));

    // Gauss-Seidel: x_v = (b_v + rho_v sum_{u != v} K_vu x_u) / (1 - rho_v K_vv).
    start = clock_type::now();
    Eigen::VectorXd g = b;
    int iteration = 0;
    for (; iteration < params.max_gauss_seidel_iterations; ++iteration) {
      double largest_change = 0.0;
      for (Eigen::Index v = 0; v < Eigen::Index(n); ++v) {
        const double others = k.row(v).dot(g) - k(v, v) * g[v];
        const double next = (b[v] + rho[v] * others) / (1.0 - rho[v] * k(v, v));
        largest_change = std::max(largest_change, std::abs(next - g[v]));
        g[v] = next;
      }
      if (largest_change <= params.gauss_seidel_tolerance * std::max(g.cwiseAbs().maxCoeff(), 1e-300)) {
        ++iteration;
        break;
      }
    }
    out.seconds_gauss_seidel += since(start);
    out.gauss_seidel_iterations = std::max(out.gauss_seidel_iterations, iteration);
    out.residual_gauss_seidel = std::max(out.residual_gauss_seidel, relative_residual(k, rho, g, b));
    for (std::size_t v = 0; v < n; ++v) {
      out.radiosity[v][c] = x[Eigen::Index(v)];
      out.radiosity_gauss_seidel[v][c] = g[Eigen::Index(v)];
    }
  }
  return true;
}

}  // namespace bounce
