#include "radiosity/hierarchical/iteration.h"

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>

#include "base/parallel.h"
#include "radiosity/hierarchical/transport.h"

// ---- I - K as a matrix-free Eigen operator (Eigen's documented pattern) ----

namespace bounce {
class transport_system;
}

namespace Eigen::internal {
template <>
struct traits<bounce::transport_system> : public Eigen::internal::traits<Eigen::SparseMatrix<double>> {};
}  // namespace Eigen::internal

namespace bounce {

// (I - K) on vectors of 3 x elements doubles (channels interleaved).
class transport_system : public Eigen::EigenBase<transport_system> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };

  explicit transport_system(const hierarchical_solver& solver) : solver_(&solver) {}
  Eigen::Index rows() const { return Eigen::Index(3 * solver_->mesh().element_count()); }
  Eigen::Index cols() const { return rows(); }

  template <typename rhs>
  Eigen::Product<transport_system, rhs, Eigen::AliasFreeProduct> operator*(const Eigen::MatrixBase<rhs>& x) const {
    return Eigen::Product<transport_system, rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  void apply(const double* in, double* out) const {
    const std::size_t n = solver_->mesh().element_count();
    std::vector<rgb>& x = x_;
    x.resize(n);
    const bool parallel = solver_->params.parallel;
    for_each_block(parallel, n, 16384, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) x[i] = rgb(in[3 * i], in[3 * i + 1], in[3 * i + 2]);
    });
    apply_transport(*solver_, x, kx_);
    for_each_block(parallel, n, 16384, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
        for (int c = 0; c < 3; ++c) out[3 * i + c] = x[i][c] - kx_[i][c];
    });
    ++applications;
  }
  mutable std::uint64_t applications = 0;

 private:
  const hierarchical_solver* solver_;
  mutable std::vector<rgb> x_, kx_;
};

}  // namespace bounce

namespace Eigen::internal {
template <typename rhs>
struct generic_product_impl<bounce::transport_system, rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<bounce::transport_system, rhs, generic_product_impl<bounce::transport_system, rhs>> {
  using Scalar = typename Product<bounce::transport_system, rhs>::Scalar;
  template <typename dest>
  static void scaleAndAddTo(dest& dst, const bounce::transport_system& lhs, const rhs& x, const Scalar& alpha) {
    const Eigen::VectorXd in = x;
    Eigen::VectorXd out(in.size());
    lhs.apply(in.data(), out.data());
    dst += alpha * out;
  }
};
}  // namespace Eigen::internal

namespace bounce {

bool bicgstab_block(const hierarchical_solver& solver, const std::vector<rgb>& rhs, std::vector<rgb>& x, int iterations,
                    double tolerance, std::uint64_t& applications) {
  const std::size_t n = solver.mesh().element_count();
  Eigen::VectorXd b(3 * Eigen::Index(n)), guess(3 * Eigen::Index(n));
  for (std::size_t e = 0; e < n; ++e)
    for (int c = 0; c < 3; ++c) {
      b[3 * Eigen::Index(e) + c] = rhs[e][c];
      guess[3 * Eigen::Index(e) + c] = x[e][c];
    }
  transport_system system(solver);
  Eigen::BiCGSTAB<transport_system, Eigen::IdentityPreconditioner> bicgstab;
  bicgstab.setMaxIterations(iterations);
  bicgstab.setTolerance(tolerance);
  bicgstab.compute(system);
  Eigen::VectorXd next = bicgstab.solveWithGuess(b, guess);
  if (bicgstab.iterations() == 0) {
    bicgstab.setTolerance(1e-14);
    next = bicgstab.solveWithGuess(b, guess);
  }
  applications += system.applications;
  if (!next.allFinite()) return false;
  for (std::size_t e = 0; e < n; ++e)
    x[e] = rgb(next[3 * Eigen::Index(e)], next[3 * Eigen::Index(e) + 1], next[3 * Eigen::Index(e) + 2]);
  return true;
}

void jacobi_sweep(const hierarchical_solver& solver, const std::vector<rgb>& rhs, std::vector<rgb>& x) {
  std::vector<rgb> kx;
  apply_transport(solver, x, kx);
  for (std::size_t e = 0; e < kx.size(); ++e) x[e] = rhs[e] + kx[e];
}

double residual_power(const hierarchical_solver& solver, const std::vector<rgb>& rhs, const std::vector<rgb>& x,
                      std::vector<rgb>& residual) {
  const patch_mesh& mesh = solver.mesh();
  std::vector<rgb> kx;
  apply_transport(solver, x, kx);
  residual.resize(kx.size());
  // Summed per block, then over the blocks in order: the same total on
  // any number of threads.
  const std::size_t block = 16384, blocks = (kx.size() + block - 1) / block;
  std::vector<double> power(blocks, 0.0);
  for_each_block(solver.params.parallel, blocks, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k)
      for (std::size_t el = k * block; el < std::min(kx.size(), (k + 1) * block); ++el) {
        residual[el] = rhs[el] + kx[el] - x[el];
        const rgb& r = residual[el];
        power[k] += (std::abs(r.r) + std::abs(r.g) + std::abs(r.b)) * mesh.element_areas[el];
      }
  });
  double total = 0.0;
  for (const double p : power) total += p;
  return total;
}

}  // namespace bounce
