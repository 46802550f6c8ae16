// Progressive shooting radiosity (Cohen, Chen, Wallace & Greenberg 1988),
// the baseline solver: received at vertices, shot from elements or from
// patches of elements (substructuring, Cohen 1986), with a posteriori mesh
// refinement while shooting (adaptive_refinement.h).
//
// Discretisation (vertex collocation, shared with the reference solver):
//   B_v = E_v + rho_v * sum_e F(v, e) * B_e,   B_e = mean of e's vertices,
// the mean of a linear function over a triangle. Each element keeps unshot
// radiosity U_e; a step shoots the element with the most unshot power
// U_e * A_e to every vertex (dB_v = rho_v F(v, e) U_e), adds what each
// vertex received to the unshot radiosity of its elements (a third each),
// and zeroes U_e. Invariant: U = M B - S, with M the vertex-to-element mean
// and S what each element has shot so far; at U = 0, B solves the system.
// A patch shoots its elements' area-weighted mean unshot radiosity through
// its outline: the same power, with the shooter's radiosity averaged over
// the patch. With one element per patch (the default) the solver converges
// to the reference solver's solution.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/progressive/adaptive_refinement.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/specular_paths.h"

namespace bounce {

struct progressive_params {
  form_factor_params form_factors;
  adaptive_params adaptive;  // a posteriori refinement during shooting (off by default)
};

// Power bookkeeping, per channel, in the scene's power units (radiosity x
// area). At every step: emitted + received == shot + unshot, to round-off.
struct power_balance {
  rgb emitted{0.0};   // emission of the elements, plus point light arriving at vertices
  rgb received{0.0};  // reflected power added to elements' unshot by shots
  rgb shot{0.0};
  rgb unshot{0.0};
  // Adaptive refinement: what the new vertices gathered from the shots
  // already made, less what the coarse elements had assumed there (signed;
  // a shadow found inside an element makes it negative).
  rgb refined{0.0};
  // The part of received (and, for point lights, of emitted) that came by
  // way of mirrors and glass: mirror images and specular paths. Already in
  // the sums above: the balance does not add it again.
  rgb specular{0.0};
};

// |emitted + received + refined - shot - unshot| / (emitted + received),
// over all channels: 0 to round-off at every step (0 before any power).
double balance_error(const power_balance& b);

// A shooter that has shot, with all the radiosity it has shot so far: what
// a vertex added later gathers from, F(v, shooter) x radiosity, so that
// every shot made is accounted for exactly.
struct shot_record {
  shooter from;
  rgb radiosity{0.0};
  rgb emission{0.0};  // the part of it that was the shooter's own emission
};

struct progressive_stats {
  std::uint64_t shots = 0;        // the point lights' shot counts as one
  std::uint64_t refinements = 0;  // adaptive passes that changed the mesh
  std::uint64_t rays = 0;
  double unshot_fraction = 1.0;  // unshot power / emitted power (sum of channels)
};

struct progressive_state {
  const patch_mesh* mesh = nullptr;
  std::shared_ptr<const patch_mesh> refined_mesh;  // set by refine_progressive: the mesh now in use
  const scene* source = nullptr;
  progressive_params params;
  form_factor_context form_factors;

  std::vector<rgb> radiosity;        // B per vertex
  std::vector<rgb> direct;           // the part of B received straight from emitters and point lights
  std::vector<rgb> unshot;           // U per element
  std::vector<rgb> unshot_emission;  // the part of U that is the element's own emission, not yet shot
  power_balance balance;
  progressive_stats stats;
  bool lights_shot = false;
  std::vector<double> scratch;      // form factors of the current shot
  std::vector<rgb> received;        // what each vertex received in the current shot
  std::vector<double> patch_power;  // unshot power per patch, for choosing the shooter
  std::vector<std::vector<int>> patch_elements;
  std::vector<shot_record> shot_log;  // every shooter that has shot (a patch split later keeps its record)
  std::vector<int> patch_log;         // per patch: its entry in shot_log, -1 before its first shot
  adaptive_progress adaptive;
  // Light through mirrors and glass (form_factor_params::specular_transfer;
  // the planar mirrors are form_factors.mirrors). The elements specular
  // paths are sent toward (null: none), what the paths have added to B per
  // vertex (carried to new vertices by interpolation when the mesh is
  // refined: the paths cannot be replayed), and where their power went.
  std::shared_ptr<const specular_surfaces> specular;
  std::vector<rgb> traced;
  std::vector<rgb> specular_received;  // per vertex, the current shot's light through mirrors and glass
  std::vector<rgb> traced_irradiance;  // per vertex, the current shot's specular paths
  specular_tally specular_paths;
};

// Sets B = E, U = M E, and prepares the form-factor method.
std::unique_ptr<progressive_state> make_progressive_state(const scene& s, const patch_mesh& mesh,
                                                          const progressive_params& params);

// Back to B = E, U = M E, keeping the form-factor method (and its BVH) and
// the mesh (refined, if it was); the refinement schedule starts again.
void restart_progressive(progressive_state& state);

// One step: point lights first (all of them, with shadow rays), then one
// patch shot, or, with adaptive refinement on and due, a refinement pass
// (state.mesh then changes). Returns false when nothing is left to do.
bool step_progressive(progressive_state& state);

// Whether every emitter and point light has shot at least once: the
// direct light is everywhere.
bool all_emission_shot(const progressive_state& state);

// Refines the state's mesh (refine_patch_mesh: the marked elements, no
// edge below min_edge) and carries the solution over exactly: each new
// vertex gathers F(v, s) x radiosity from every shooter s in the shot log
// (and the point lights again), old vertices keep theirs, and each element's
// unshot becomes its origin's plus the change in its vertices' mean, so
// U = M B - S still holds. The refined mesh is state.refined_mesh (the old
// one may then be released). Returns false with `error` if the mesh would
// grow too large; the state is then unchanged. `new_vertices` (may be
// null) receives how many vertices were added.
bool refine_progressive(progressive_state& state, std::span<const int> marked, double min_edge, std::string& error,
                        std::size_t* new_vertices = nullptr);

}  // namespace bounce
