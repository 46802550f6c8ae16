// The solver options of every command that solves (view, render, trace,
// solve): they set the core's solver settings directly, and are checked
// against the solver and form-factor method they apply to.
#pragma once

#include <span>
#include <string>

#include "radiosity/solver_settings.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

void add_solver_options(CLI::App& command, solver_settings& settings);

// The names of the options add_solver_options adds, for messages about
// options that a combination ignores (given_options).
std::span<const char* const> solver_option_names();

// Solver options that the chosen solver or form-factor method ignores; an
// error message or an empty string. Options of the progressive solver
// alone choose it (settings.method) unless another was asked for by name.
std::string check_solver_options(const CLI::App& command, solver_settings& settings);

// The commands with a picture (render, trace) let their camera lead the
// hierarchical solver's refinement (settings.view); --view-independent
// refines every part of the scene alike, as `solve` and the window do. The
// check refuses it with another solver.
void add_view_independent_option(CLI::App& command, bool& view_independent);
std::string check_view_independent_option(const CLI::App& command, const solver_settings& settings);

}  // namespace bounce
