// The final gather: once the final links are solved, each element gathers
// over the links of itself and its ancestors with the kernel evaluated at
// its own centre and normal, rather than taking its share of what its
// ancestors received at theirs. Links from inner nodes take the disc
// estimate at the element, corrected as the link's strata estimate
// corrects it at its receiver's centre (the correction is the source's
// shape, which changes slowly over a receiver that the oracle kept small
// against the distance). Through mirror chains: the kernel to the source's
// image (Lambert's formula on the reflected triangle for leaves).
#pragma once

#include <cstdint>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// The kernel evaluations a final gather costs: over elements, the links of
// the element and its ancestors.
std::uint64_t final_gather_cost(const hierarchical_solver& solver);

// Fills solver.gathered with each element's reflected light (total: from
// the solution; direct: from the emitters alone over plain links;
// mirrored: from the emitters through mirror links), normalised like the
// operator. Past params.gather_budget it is not made and returns false.
bool final_gather(hierarchical_solver& solver);

}  // namespace bounce
