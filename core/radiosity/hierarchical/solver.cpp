#include "radiosity/hierarchical/solver.h"

#include <cmath>

#include "radiosity/hierarchical/closed_scene.h"
#include "radiosity/hierarchical/element_refinement.h"
#include "radiosity/hierarchical/iteration.h"
#include "radiosity/hierarchical/link_refinement.h"
#include "radiosity/hierarchical/sources.h"
#include "radiosity/hierarchical/specular_passes.h"
#include "radiosity/hierarchical/transport.h"

namespace bounce {
namespace {

void update_residual(hierarchical_solver& solver) {
  const double power = residual_power(solver, right_hand_side(solver), solver.light.total, solver.residual);
  ++solver.progress.operator_applications;
  solver.residual_fraction = solver.sources.emitted_power > 0.0 ? power / solver.sources.emitted_power : 0.0;
}

// The solution is at least its emission plus the direct light (K >= 0,
// B >= 0): B >= E + direct, element by element. BiCGSTAB's iterates are not
// monotone and can dip below that early on (a still stopped at 5% showed
// negative indirect light), and so can a solution when refined links bring
// more direct light than it holds. Raising such an element to the bound
// moves it towards the solution, never away.
void raise_to_the_direct_light(hierarchical_solver& solver) {
  const light_parts& light = solver.light;
  const std::vector<rgb>& emission = solver.sources.emission;
  for (std::size_t e = 0; e < light.total.size(); ++e) {
    rgb least = emission[e] + light.direct[e];
    if (e < light.mirrored.size()) least += light.mirrored[e];
    solver.light.total[e] = glm::max(light.total[e], least);
  }
}

// The direct light (plain links from the emitters, and the point lights
// straight), and the emitters' light through mirror links.
void update_direct(hierarchical_solver& solver) {
  light_parts& light = solver.light;
  std::vector<rgb>& emitted = solver.buffers.emitted;
  gather_push(solver, solver.sources.emission, light.direct, &light.mirrored, &emitted);
  ++solver.progress.operator_applications;
  const link_hierarchy& h = solver.hierarchy;
  for (std::size_t e = 0; e < light.direct.size(); ++e) {
    light.direct[e] = h.rho[e] * normalised(light.direct[e], emitted[e], h.normalizer[e]) + direct_lamp(solver, e);
    light.mirrored[e] = h.rho[e] * light.mirrored[e];
  }
}

bool tolerance_final(const hierarchical_solver& solver) {
  return solver.progress.tolerance <= solver.params.tolerance * (1.0 + 1e-9);
}

// The first step: the coarsest links, then one Jacobi sweep from B = E:
// the direct light.
void first_links(hierarchical_solver& solver) {
  solver.progress.links_final = tolerance_final(solver);
  refine_links(solver, solver.progress.tolerance);
  update_direct(solver);
  jacobi_sweep(solver, right_hand_side(solver), solver.light.total);
  ++solver.progress.operator_applications;
  update_residual(solver);
}

// Refines: first the elements the last links marked (against the solution
// as it is now), then the links at the next tolerance, or at the final one
// again if elements were split or a new view leads.
void refine(hierarchical_solver& solver) {
  solver.progress.previous_residual = INFINITY;
  const bool remeshed = splits_pending(solver) && split_marked_elements(solver);
  const double next = std::max(solver.params.tolerance, solver.progress.tolerance / solver.params.refine_factor);
  const bool cut_short = tolerance_final(solver) && !solver.progress.links_final;  // by a time limit
  if (next < solver.progress.tolerance || remeshed || solver.view.retarget || cut_short) {
    solver.progress.tolerance = next;
    solver.progress.links_final = tolerance_final(solver);
    refine_links(solver, solver.progress.tolerance);
    update_direct(solver);
    raise_to_the_direct_light(solver);  // new links may bring more than the solution holds
  }
  update_residual(solver);
}

// A block of BiCGSTAB iterations; where it breaks down or makes the
// residual worse (it can, on a non-normal operator), a Jacobi sweep.
void iterate(hierarchical_solver& solver, double refine_below) {
  const std::vector<rgb> rhs = right_hand_side(solver);
  // Before the links are final, this tolerance only needs solving as far
  // as the next refinement (Eigen's relative 2-norm residual).
  const double tolerance = refinement_done(solver) ? 1e-14 : 0.5 * refine_below;
  const std::vector<rgb> before = solver.light.total;
  const double residual_before = solver.residual_fraction;
  if (bicgstab_block(solver, rhs, solver.light.total, solver.params.iterations_per_step, tolerance,
                     solver.progress.operator_applications)) {
    raise_to_the_direct_light(solver);
    update_residual(solver);
    if (solver.residual_fraction < residual_before) return;
  }
  solver.light.total = before;
  jacobi_sweep(solver, rhs, solver.light.total);
  ++solver.progress.operator_applications;
  update_residual(solver);
  ++solver.progress.jacobi_fallbacks;
}

}  // namespace

std::unique_ptr<hierarchical_solver> make_hierarchical_solver(const scene& s, const patch_mesh& mesh,
                                                              const form_factor_context& context,
                                                              const hierarchical_params& params) {
  check_mesh_contract(mesh);
  auto solver = std::make_unique<hierarchical_solver>();
  solver->meshes.current = solver->meshes.input = &mesh;
  solver->source = &s;
  solver->params = params;
  solver->context = context;
  solver->context.vertex_areas.clear();  // the solver works per element
  solver->meshes.min_edge = params.min_edge > 0.0 ? params.min_edge : mesh.max_edge / 8.0;
  solver->meshes.min_edge_follows_view = !(params.min_edge > 0.0);
  if (params.mirror_links && context.mirrors && context.params.specular_transfer)
    solver->hierarchy.chains = mirror_chains(*context.mirrors, context.params.mirror_depth);
  solver->sources.has_path_targets = path_targets(*solver) != nullptr;
  solver->sources.specular_lamp_input = specular_lamp_of(*solver, solver->progress.rays);
  solver->sources.specular_lamp = solver->sources.specular_lamp_input;
  solver->meshes.input_element.resize(mesh.element_count());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) solver->meshes.input_element[e] = int(e);
  rebuild_for_mesh(*solver, build_cluster_tree(mesh));
  solver->progress.closed = params.normalize_closed && scene_is_closed(*solver);
  restart_hierarchical(*solver);
  return solver;
}

void restart_hierarchical(hierarchical_solver& solver) {
  if (solver.meshes.current != solver.meshes.input) {
    solver.meshes.current = solver.meshes.input;
    solver.meshes.refined.reset();
    solver.sources.specular_lamp = solver.sources.specular_lamp_input;
    solver.meshes.input_element.resize(solver.mesh().element_count());
    for (std::size_t e = 0; e < solver.meshes.input_element.size(); ++e) solver.meshes.input_element[e] = int(e);
    rebuild_for_mesh(solver, build_cluster_tree(solver.mesh()));
  }
  if (solver.progress.specular_passes > 0) set_specular_lamp(solver, solver.sources.specular_lamp_input);
  const std::size_t nodes = solver.hierarchy.tree.nodes.size();
  clear_links(solver.hierarchy.links, nodes);
  clear_links(solver.hierarchy.mirror_links, nodes);
  clear_links(solver.hierarchy.emitter_links, nodes);
  solver.split_marks.clear();
  solver.view.node.clear();  // the view stays; its weights come with the links
  solver.view.retarget = false;
  const std::size_t n = solver.mesh().element_count();
  solver.hierarchy.normalizer.assign(n, closed_scale{});
  solver.light.total = right_hand_side(solver);
  solver.light.direct.resize(n);
  for (std::size_t e = 0; e < n; ++e) solver.light.direct[e] = direct_lamp(solver, e);
  solver.light.mirrored.assign(n, rgb(0.0));
  solver.residual.assign(n, rgb(0.0));
  solver.residual_fraction = 1.0;
  solver.gathered = {};
  solver.gathered_at.clear();
  const std::uint64_t rays = solver.progress.rays;
  const bool closed = solver.progress.closed;
  solver.progress = hierarchy_progress{};
  solver.progress.rays = rays;
  solver.progress.closed = closed;
  solver.progress.tolerance = solver.params.tolerance * std::pow(solver.params.refine_factor, solver.params.rounds);
}

bool refinement_done(const hierarchical_solver& solver) {
  return solver.progress.links_final && !splits_pending(solver) && !solver.view.retarget;
}

bool step_hierarchical(hierarchical_solver& solver, double refine_below) {
  if (!(refinement_done(solver) && solver.residual_fraction <= 1e-13)) ++solver.progress.steps;
  if (solver.hierarchy.links.empty() && solver.progress.refinements == 0) {
    first_links(solver);
    return true;
  }
  // Refine once this tolerance is solved far enough, or when iterating no
  // longer helps (a residual that falls by less than 5% a step).
  const bool stalled = solver.residual_fraction > 0.95 * solver.progress.previous_residual;
  solver.progress.previous_residual = solver.residual_fraction;
  if ((solver.residual_fraction <= refine_below || stalled) && !refinement_done(solver)) {
    refine(solver);
    return true;
  }
  // The final links solved: diffuse light that mirrors and glass pass on
  // joins the right-hand side, one pass at a time.
  if (refinement_done(solver) && solver.residual_fraction <= refine_below && !specular_passes_done(solver)) {
    make_specular_pass(solver);
    solver.progress.previous_residual = INFINITY;
    update_residual(solver);
    return true;
  }
  if (refinement_done(solver) && solver.residual_fraction <= 1e-13) return false;
  iterate(solver, refine_below);
  return true;
}

}  // namespace bounce
