// The hemicube (Cohen & Greenberg 1985), on the CPU: form factors from one
// shooter to every vertex through a z-buffer over the five faces of a half
// cube at the shooter's centroid. The form-factor layer calls it when the
// method is form_factor_method::hemicube.
#pragma once

#include <cstdint>
#include <span>

#include "radiosity/transfer/form_factor.h"

namespace bounce {

// Fills out[v] with F(v, from) for every vertex of the context's mesh;
// returns the number of pixels rendered (the method's cost, counted as rays).
std::uint64_t hemicube_form_factors(const form_factor_context& context, const shooter& from, std::span<double> out);

}  // namespace bounce
