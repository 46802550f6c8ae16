#include "radiosity/solver.h"

#include <chrono>

#include "radiosity/hierarchical/publication.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/hierarchical/view_importance.h"
#include "radiosity/transfer/buried_vertices.h"
#include "radiosity/transfer/mirror_images.h"

namespace bounce {

struct hierarchical_run {
  std::unique_ptr<hierarchical_solver> solver;
  double refine_below = 0.02;
  vertex_light published;  // per vertex of solver->mesh(), after every step
  bool stepped = false;    // the first links have carried the direct light
};

namespace {

template <typename... functions>
struct overloaded : functions... {
  using functions::operator()...;
};
template <typename... functions>
overloaded(functions...) -> overloaded<functions...>;

solver_stats stats_of(const progressive_state& p) {
  solver_stats out;
  out.steps = p.stats.shots;
  out.refinements = p.stats.refinements;
  out.rays = p.stats.rays;
  out.remaining = p.stats.unshot_fraction;
  out.remaining_final = p.lights_shot;
  return out;
}

solver_stats stats_of(const hierarchical_run& run) {
  const hierarchical_solver& h = *run.solver;
  solver_stats out;
  out.steps = h.progress.steps;
  out.refinements = std::uint64_t(std::max(0, h.progress.refinements - 1));
  out.rays = h.progress.rays;
  out.remaining = run.stepped ? h.residual_fraction : 1.0;
  out.remaining_final = run.stepped && solution_final(h);
  out.links = h.hierarchy.links.size();
  out.link_tolerance = h.progress.tolerance;
  out.cut_short = h.progress.links_cut_short;
  return out;
}

// The published solution of the hierarchical solver, after a step or a restart.
void publish(hierarchical_run& run) {
  run.published = publish_vertex_light(*run.solver);
}

// The statistics after a step or a restart: the solver's own, and the time
// kept across steps.
void update_stats(radiosity_solver& solver, double seconds) {
  solver.stats = std::visit([](const auto& state) { return stats_of(*state); }, solver.state);
  solver.stats.seconds = seconds;
}

}  // namespace

radiosity_solver::radiosity_solver() = default;
radiosity_solver::~radiosity_solver() = default;

std::unique_ptr<radiosity_solver> make_radiosity_solver(const scene& s, const patch_mesh& mesh,
                                                        const radiosity_params& params) {
  auto solver = std::make_unique<radiosity_solver>();
  if (params.method == solver_method::progressive) {
    solver->state = make_progressive_state(s, mesh, {params.form_factors, params.adaptive});
  } else {
    // The form factors' context (its occlusion scene, the mirrors) is the
    // progressive solver's; the hierarchical one works per element.
    form_factor_context context = make_form_factor_context(mesh, params.form_factors);
    const form_factor_params& p = params.form_factors;
    if (p.specular_transfer && has_specular_materials(s) && p.mirror_depth > 0)
      context.mirrors = find_planar_mirrors(s, mesh);
    auto run = std::make_unique<hierarchical_run>();
    run->solver = make_hierarchical_solver(s, mesh, context, params.hierarchical);
    if (params.view) set_view(*run->solver, *params.view);
    run->refine_below = params.hierarchical.refine_below;
    publish(*run);
    solver->state = std::move(run);
  }
  update_stats(*solver, 0.0);
  return solver;
}

void restart_solver(radiosity_solver& solver) {
  std::visit(overloaded{[](std::unique_ptr<progressive_state>& p) { restart_progressive(*p); },
                        [](std::unique_ptr<hierarchical_run>& run) {
                          restart_hierarchical(*run->solver);
                          run->stepped = false;
                          publish(*run);
                        }},
             solver.state);
  update_stats(solver, 0.0);
}

void set_solver_view(radiosity_solver& solver, const std::optional<camera>& view) {
  auto* run = std::get_if<std::unique_ptr<hierarchical_run>>(&solver.state);
  if (!run) return;
  set_view(*(*run)->solver, view);
  update_stats(solver, solver.stats.seconds);  // no longer final
}

bool step_solver(radiosity_solver& solver, std::chrono::steady_clock::time_point deadline) {
  const auto start = std::chrono::steady_clock::now();
  const bool stepped = std::visit(overloaded{[](std::unique_ptr<progressive_state>& p) { return step_progressive(*p); },
                                             [&](std::unique_ptr<hierarchical_run>& run) {
                                               run->solver->deadline = deadline;
                                               if (!step_hierarchical(*run->solver, run->refine_below)) return false;
                                               run->stepped = true;
                                               publish(*run);
                                               return true;
                                             }},
                                  solver.state);
  if (!stepped) return false;
  const form_factor_context& context = std::visit(
      overloaded{
          [](const std::unique_ptr<progressive_state>& p) -> const form_factor_context& { return p->form_factors; },
          [](const std::unique_ptr<hierarchical_run>& run) -> const form_factor_context& {
            return run->solver->context;
          }},
      solver.state);
  find_buried_vertices(solved_mesh(solver), *context.mesh, *context.occlusion, context.offset, solver.buried);
  update_stats(solver,
               solver.stats.seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return true;
}

bool stop_reached(const radiosity_solver& solver, const stop_criterion& stop) {
  const solver_stats& st = solver.stats;
  // Before it is final, the remaining fraction says little: a dim emitter
  // may not have shot yet, or the links may still be coarse.
  if (stop.remaining > 0.0 && st.remaining_final && st.remaining <= stop.remaining) return true;
  if (stop.max_steps > 0 && st.steps >= stop.max_steps) return true;
  return stop.seconds > 0.0 && st.seconds >= stop.seconds;
}

void run_solver(radiosity_solver& solver, const stop_criterion& stop,
                const std::function<void(const radiosity_solver&)>& on_step) {
  // The time left, as a deadline a long step (a link refinement) heeds.
  const auto start = std::chrono::steady_clock::now();
  const auto deadline = stop.seconds > 0.0
                            ? start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                          std::chrono::duration<double>(stop.seconds - solver.stats.seconds))
                            : std::chrono::steady_clock::time_point::max();
  while (!stop_reached(solver, stop) && step_solver(solver, deadline))
    if (on_step) on_step(solver);
}

solver_method method_of(const radiosity_solver& solver) {
  return std::holds_alternative<std::unique_ptr<progressive_state>>(solver.state) ? solver_method::progressive
                                                                                  : solver_method::hierarchical;
}

const patch_mesh& solved_mesh(const radiosity_solver& solver) {
  return std::visit(
      overloaded{[](const std::unique_ptr<progressive_state>& p) -> const patch_mesh& { return *p->mesh; },
                 [](const std::unique_ptr<hierarchical_run>& run) -> const patch_mesh& { return run->solver->mesh(); }},
      solver.state);
}

std::shared_ptr<const patch_mesh> refined_mesh(const radiosity_solver& solver) {
  return std::visit(
      overloaded{[](const std::unique_ptr<progressive_state>& p) { return p->refined_mesh; },
                 [](const std::unique_ptr<hierarchical_run>& run) { return run->solver->meshes.refined; }},
      solver.state);
}

std::shared_ptr<const radiosity_snapshot> make_snapshot(const radiosity_solver& solver) {
  return std::visit(overloaded{[&](const std::unique_ptr<progressive_state>& p) {
                                 return make_snapshot(*p->mesh, p->radiosity, p->direct, {}, p->unshot, solver.stats,
                                                      solver.buried);
                               },
                               [&](const std::unique_ptr<hierarchical_run>& run) {
                                 const vertex_light& light = run->published;
                                 return make_snapshot(run->solver->mesh(), light.radiosity, light.direct, light.caustic,
                                                      run->solver->residual, solver.stats, solver.buried);
                               }},
                    solver.state);
}

bool all_emission_out(const radiosity_solver& solver) {
  return std::visit(overloaded{[](const std::unique_ptr<progressive_state>& p) { return all_emission_shot(*p); },
                               [](const std::unique_ptr<hierarchical_run>& run) { return run->stepped; }},
                    solver.state);
}

const form_factor_context& form_factors_of(const radiosity_solver& solver) {
  return std::visit(overloaded{[](const std::unique_ptr<progressive_state>& p) -> const form_factor_context& {
                                 return p->form_factors;
                               },
                               [](const std::unique_ptr<hierarchical_run>& run) -> const form_factor_context& {
                                 return run->solver->context;
                               }},
                    solver.state);
}

const progressive_state* progressive_of(const radiosity_solver& solver) {
  const auto* p = std::get_if<std::unique_ptr<progressive_state>>(&solver.state);
  return p ? p->get() : nullptr;
}

const hierarchical_solver* hierarchical_of(const radiosity_solver& solver) {
  const auto* run = std::get_if<std::unique_ptr<hierarchical_run>>(&solver.state);
  return run ? (*run)->solver.get() : nullptr;
}

}  // namespace bounce
