// The solver statistics that `--stats FILE` writes (solve, render, trace):
// one JSON layout for every command that solves.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "mesh/patch_mesh.h"
#include "radiosity/solve.h"
#include "radiosity/solver.h"
#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace bounce {

// Mesh, settings, steps, time, and what each solver keeps of its own (the
// progressive power balance, the hierarchical links) of a finished run.
// `meshed` is the mesh as the mesher built it (the solver's may be refined).
nlohmann::json solver_stats_json(const scene& s, const solver_settings& settings, const patch_mesh& meshed,
                                 const radiosity_solver& solver, double mesh_seconds);

// start_solve for a command: when the scene cannot be meshed, prints the
// error naming the scene on standard error and returns false. Ends the
// set-up's time limit (time_limit.h).
bool start_command_solve(const scene& s, const solver_settings& settings, solve_setup& out);

// Warns on standard error about what the mesher had to leave imperfect
// (non-manifold faces, coplanar overlaps it could not cut).
void warn_about_mesh(const scene& s, const patch_mesh& mesh);

// Warns on standard error about what the solver had to leave coarse: the
// link limit, element refinement stopped, a link refinement cut short by
// --time.
void warn_about_solve(const scene& s, const radiosity_solver& solver);

// Writes `stats` to `path`; false with `error` (naming the file) on failure.
bool write_stats(const std::string& path, const nlohmann::json& stats, std::string& error);

}  // namespace bounce
