// Light by way of curved mirrors and glass, which links do not carry
// (links through mirrors carry planar mirrors alone: link_refinement.h).
// The emitters' and point lights' light through mirrors and glass is
// traced once, on the input mesh, into the right-hand side
// (sources.specular_lamp). Once the final links are solved, each pass
// sends every patch's reflected light through mirrors and glass the same
// way and puts it in the right-hand side too (D S+ D), starting from the
// solution the pass before led to: params.specular_bounces passes carry
// light that mirrors and glass pass on between diffuse surfaces that many
// times.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "radiosity/hierarchical/state.h"
#include "radiosity/transfer/specular_paths.h"

namespace bounce {

// The specular surfaces that paths are sent toward (null: none, or paths off).
std::shared_ptr<const specular_surfaces> path_targets(const hierarchical_solver& solver);

// The emitters' and point lights' light by way of mirrors and glass, per
// element of the input mesh, or nothing when the transfer is off or the
// scene has nothing specular. Adds the rays cast to `rays`.
std::vector<rgb> specular_lamp_of(const hierarchical_solver& solver, std::uint64_t& rays);

// Whether the passes are all made, or none is due (nothing specular, the
// transfer off, or links through mirrors with no curved mirror or glass
// left for paths): the right-hand side is then final.
bool specular_passes_done(const hierarchical_solver& solver);

// Makes the next pass: the patches' reflected light through mirrors and
// glass, plus the emitters' (specular_lamp_input), becomes the lamp's
// specular part.
void make_specular_pass(hierarchical_solver& solver);

// Sets the lamp's part by way of mirrors and glass to `per_input` (per
// element of the input mesh; the pieces of a split element take its value).
void set_specular_lamp(hierarchical_solver& solver, const std::vector<rgb>& per_input);

}  // namespace bounce
