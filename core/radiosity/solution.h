// What a radiosity solver publishes, whichever solver it is: its progress
// in one vocabulary (solver_stats) and an immutable copy of its solution
// at the vertices of the mesh it solves (radiosity_snapshot), for the
// view, the stills, the bench and the files written.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

// A run's progress. Each solver states what its words mean:
// - steps: progressive: shots (the point lights' counts as one; a
//   refinement pass is not a step); hierarchical: its steps (links made or
//   refined, a block of iterations, a pass through mirrors and glass).
// - remaining: what is left to do as a fraction of the emitted power.
//   Progressive: the unshot power (its magnitude: refinement can leave
//   some negative); hierarchical: the power of the residual E + K B - B.
// - remaining_final: `remaining` measures what is left of the final
//   answer, so a run may stop on it. Progressive: once the point lights
//   have shot; hierarchical: once the links, the elements and the passes
//   through mirrors and glass are final.
struct solver_stats {
  std::uint64_t steps = 0;
  std::uint64_t refinements = 0;  // mesh refinements (progressive) or link refinements (hierarchical) after the first
  std::uint64_t rays = 0;
  double seconds = 0.0;  // wall time spent in steps
  double remaining = 1.0;
  bool remaining_final = false;
  // Hierarchical: its links and the oracle's tolerance (0 otherwise).
  std::uint64_t links = 0;
  double link_tolerance = 0.0;
  // The last step was ended early by the run's deadline (hierarchical: a
  // link refinement that stopped splitting): links coarser than asked.
  bool cut_short = false;
};

// An immutable copy of a solution, per vertex of the mesh the solver had
// at the time (refined, if it refines); whoever shows it keeps that mesh
// with it.
struct radiosity_snapshot {
  std::uint64_t version = 0;   // steps and refinements so far; increases with every step
  std::vector<rgb> radiosity;  // B
  std::vector<rgb> direct;     // the part of B straight from emitters and point lights
  std::vector<rgb> caustic;    // the part by way of mirrors and glass, where the solver keeps it apart (may be empty)
  std::vector<rgb> remaining;  // the mean over each vertex's elements of their remaining radiosity (false colour)
  rgb ambient{0.0};            // ambient_radiosity, for display
  solver_stats stats;
};

// A snapshot of per-vertex arrays and the per-element remaining radiosity
// (unshot, or residual) on `mesh`. Vertices flagged in `buried` (one flag
// per vertex, or empty) take their values from their neighbours outside
// (transfer/buried_vertices.h).
std::shared_ptr<const radiosity_snapshot> make_snapshot(const patch_mesh& mesh, std::span<const rgb> radiosity,
                                                        std::span<const rgb> direct, std::span<const rgb> caustic,
                                                        std::span<const rgb> remaining, const solver_stats& stats,
                                                        const std::vector<bool>& buried = {});

// Cohen 1988's ambient term, for display only: the remaining radiosity
// (per element) spread evenly and reflected with the mean reflectance; zero
// where that sum is negative (an overshooting iterate): light still to
// come is never negative.
rgb ambient_radiosity(const patch_mesh& mesh, std::span<const rgb> remaining);

// Area-weighted mean irradiance that did not come straight from an emitter
// (what arrives after one or more reflections): the constant ambient term
// of a one-pass Whitted still, taken from a (coarse) solution.
rgb mean_indirect_irradiance(const patch_mesh& mesh, const radiosity_snapshot& solution);

}  // namespace bounce
