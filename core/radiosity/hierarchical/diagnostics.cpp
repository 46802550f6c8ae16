#include "radiosity/hierarchical/diagnostics.h"

#include <atomic>

#include <Eigen/Dense>

#include "base/check.h"
#include "radiosity/hierarchical/oracle.h"

namespace bounce {

std::vector<double> link_density(const hierarchical_solver& solver) {
  const cluster_tree& tree = solver.hierarchy.tree;
  std::vector<double> per_node(tree.nodes.size(), 0.0);
  // Links per unit area of their receiver, accumulated down the tree.
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const double links = double(solver.hierarchy.links.count_of(i));
    const double own = tree.nodes[i].area > 0.0 ? links / tree.nodes[i].area : 0.0;
    per_node[i] = own + (tree.nodes[i].parent >= 0 ? per_node[std::size_t(tree.nodes[i].parent)] : 0.0);
  }
  std::vector<double> out(solver.mesh().element_count());
  for (std::size_t e = 0; e < out.size(); ++e) out[e] = per_node[std::size_t(tree.leaf_of_element[e])];
  return out;
}

std::vector<rgb> element_level_solution(const hierarchical_solver& solver) {
  const std::size_t n = solver.mesh().element_count();
  BOUNCE_CHECK_LE(n, std::size_t(4000));  // a dense matrix
  const cluster_tree& tree = solver.hierarchy.tree;
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(n));
  std::atomic<std::uint64_t> rays{0};
  for (std::size_t i = 0; i < n; ++i) {
    const int ri = tree.leaf_of_element[i];
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const int sj = tree.leaf_of_element[j];
      const link_estimate e = estimate(solver, ri, sj);
      if (e.none || !(e.factor > 0.0)) continue;
      f(Eigen::Index(i), Eigen::Index(j)) =
          double(float(e.factor)) *
          double(pair_visibility(solver, ri, sj, solver.params.leaf_visibility_rays, -1, rays));
    }
  }
  if (solver.progress.closed)
    for (Eigen::Index i = 0; i < f.rows(); ++i) {
      const double sum = f.row(i).sum();
      if (sum > 0.0) f.row(i) /= sum;
    }
  std::vector<rgb> b(n);
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd a = -f;
    Eigen::VectorXd right = Eigen::VectorXd::Zero(Eigen::Index(n));
    for (std::size_t i = 0; i < n; ++i) {
      a.row(Eigen::Index(i)) *= solver.hierarchy.rho[i][c];
      a(Eigen::Index(i), Eigen::Index(i)) += 1.0;
      right[Eigen::Index(i)] = solver.sources.emission[i][c] + solver.sources.lamp[i][c];
    }
    const Eigen::VectorXd x = a.partialPivLu().solve(right);
    for (std::size_t i = 0; i < n; ++i) b[i][c] = x[Eigen::Index(i)];
  }
  return b;
}

}  // namespace bounce
