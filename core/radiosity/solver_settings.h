// One settings type for a radiosity run: how the scene is meshed, how form
// factors are computed, whether the mesh adapts, and when to stop. The
// command line, the panel, the viewer's worker and the bench all hold one
// of these and turn it into the core's parameters the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "mesh/patch_mesh.h"
#include "radiosity/progressive/adaptive_refinement.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

struct radiosity_params;

// Which solver runs: hierarchical radiosity with clustering (the default:
// hierarchical/solver.h) or progressive shooting (progressive/progressive.h),
// the baseline.
enum class solver_method { hierarchical, progressive };

// When a run stops. Every limit counts from the solver's (re)start: the
// steps it has made and the time it has spent stepping (solver_stats), so
// a limit means the same whether the run is driven by run_solve, the
// window's worker or the bench (stop_reached, solver.h).
struct stop_criterion {
  double remaining = 0.0;       // at or below this remaining fraction, once it is final (0: no limit)
  std::uint64_t max_steps = 0;  // 0: no limit
  double seconds = 0.0;         // solver time; 0: no limit
};

struct solver_settings {
  solver_method method = solver_method::hierarchical;
  // Mesh, in scene units, as asked for; mesher_params_for resolves the
  // defaults that depend on the scene.
  double max_edge = 0.0;     // longest element edge; 0: the scene's default
  double patch_edge = -1.0;  // shooting patches (substructuring); 0: elements shoot; < 0: the default
  // Elements are not split below this edge: the hierarchical solver's
  // element refinement and the progressive solver's adaptive meshing both
  // read it. 0: an eighth of the element size (hierarchical, with a view:
  // finer where the view sees elements large).
  double min_edge = 0.0;
  // Cut the strong lights' umbra and penumbra outlines into the mesh
  // (mesh/shadow_outlines.h).
  bool shadow_outlines = false;
  form_factor_params form_factors;
  adaptive_params adaptive;  // progressive: adaptive meshing (its min_edge comes from min_edge above)
  // Hierarchical: the oracle's final tolerance, a fraction of the emitted
  // power that one link may carry unrefined (the accuracy knob).
  double link_tolerance = 1e-5;
  stop_criterion stop{0.01, 0, 0.0};  // 1% of the power left; no step or time limit
  // Hierarchical: the camera whose view leads refinement (importance,
  // hierarchical/view_importance.h); none: every part of the scene alike.
  std::optional<camera> view;
};

// The mesher's parameters for `s`: element size from the scene when not
// given; patches of 4 x 4 elements shoot (or, with adaptive meshing, the
// elements themselves, which refine with the receivers).
mesher_params mesher_params_for(const solver_settings& settings, const scene& s);

// The solver's parameters (form factors, a posteriori refinement, links).
radiosity_params radiosity_params_for(const solver_settings& settings);

// Names of the solvers, as the command line and the panel show them.
struct solver_method_name {
  solver_method method;
  std::string_view name;
};
std::span<const solver_method_name> solver_method_names();
std::string_view name_of(solver_method method);
std::optional<solver_method> solver_method_named(std::string_view name);

// Names of the form-factor methods, as the command line and the panel show them.
struct form_factor_method_name {
  form_factor_method method;
  std::string_view name;
};
std::span<const form_factor_method_name> form_factor_method_names();
std::string_view name_of(form_factor_method method);
std::optional<form_factor_method> form_factor_method_named(std::string_view name);

}  // namespace bounce
