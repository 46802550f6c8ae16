// Solving B = E + K B for a fixed set of links: BiCGSTAB on I - K (Eigen,
// matrix-free: every product is one application of the transport
// operator), so that high reflectance does not stall it, and the Jacobi
// sweep B = E + K B where BiCGSTAB breaks down, which converges whenever
// every element's form factors sum to less than 1 / rho. Eigen stays
// inside iteration.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// At most `iterations` BiCGSTAB iterations on (I - K) x = rhs (both per
// element), starting from x, stopping at Eigen's relative 2-norm residual
// `tolerance`; when Eigen finds x solved at once, the block runs again at
// 1e-14 (its norm says solved where the area-weighted residual may not).
// Returns false, leaving x as it was, if the result is not finite. Adds
// the operator applications made to `applications`.
bool bicgstab_block(const hierarchical_solver& solver, const std::vector<rgb>& rhs, std::vector<rgb>& x, int iterations,
                    double tolerance, std::uint64_t& applications);

// One Jacobi sweep: x = rhs + K x.
void jacobi_sweep(const hierarchical_solver& solver, const std::vector<rgb>& rhs, std::vector<rgb>& x);

// residual = rhs + K x - x per element, and its power (channel sums of its
// magnitude x area, summed in a fixed order on any number of threads).
double residual_power(const hierarchical_solver& solver, const std::vector<rgb>& rhs, const std::vector<rgb>& x,
                      std::vector<rgb>& residual);

}  // namespace bounce
