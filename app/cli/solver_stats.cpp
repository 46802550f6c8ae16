#include "cli/solver_stats.h"

#include <cstdio>
#include <fstream>

#include <tbb/global_control.h>

#include "base/whole_file.h"
#include "cli/console.h"
#include "cli/time_limit.h"
#include "radiosity/transfer/specular_paths.h"

namespace bounce {
namespace {

nlohmann::json to_json(const rgb& c) {
  return {c.r, c.g, c.b};
}

}  // namespace

nlohmann::json solver_stats_json(const scene& s, const solver_settings& settings, const patch_mesh& meshed,
                                 const radiosity_solver& solver, double mesh_seconds) {
  const solver_stats& st = solver.stats;
  const progressive_state* progressive = progressive_of(solver);
  const patch_mesh& solved = solved_mesh(solver);  // refined, with adaptive meshing or split elements
  nlohmann::json passes = nlohmann::json::array();
  if (progressive)
    for (const refinement_pass& pass : progressive->adaptive.history)
      passes.push_back({{"unshot_fraction", pass.unshot_fraction},
                        {"gradient_marks", pass.gradient},
                        {"shadow_marks", pass.shadow},
                        {"elements_before", pass.elements_before},
                        {"elements_after", pass.elements_after},
                        {"new_vertices", pass.new_vertices},
                        {"seconds", pass.seconds}});
  nlohmann::json out = {
      {"scene", s.source},
      {"solver", name_of(method_of(solver))},
      {"max_edge", solved.max_edge},
      {"elements", solved.element_count()},
      {"elements_meshed", meshed.element_count()},
      {"vertices", solved.vertex_count()},
      {"patches", solved.patch_count()},
      {"contact_footprints", meshed.contact_footprints},
      {"contact_area_removed", meshed.contact_area_removed},
      {"shadow_outline_lights", meshed.shadow_lights},
      {"shadow_outlines", meshed.shadow_outlines},
      {"shadow_triangles_split", meshed.shadow_triangles_split},
      {"adaptive", settings.adaptive.enabled},
      {"refinement_passes", passes},
      {"patch_edge", mesher_params_for(settings, s).patch_edge},
      {"mesh_seconds", mesh_seconds},
      {"steps", st.steps},
      {"remaining", st.remaining},
      {"seconds", st.seconds},
      {"rays", st.rays},
      // What the run could use: one per core, or --threads.
      {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)},
  };
  if (const hierarchical_solver* hierarchical = hierarchical_of(solver)) {
    const hierarchical_solver& h = *hierarchical;
    out["hierarchical"] = {{"links", h.hierarchy.links.size()},
                           {"link_bytes", h.hierarchy.links.size() * sizeof(hierarchy_link)},
                           // Links through chains of planar mirrors (not in "links").
                           {"mirror_links", h.hierarchy.mirror_links.size()},
                           {"mirror_chains", h.hierarchy.chains.size()},
                           {"link_tolerance", h.progress.tolerance},
                           {"links_final", h.progress.links_final},
                           {"refinements", h.progress.refinements},
                           {"operator_applications", h.progress.operator_applications},
                           {"tree_nodes", h.hierarchy.tree.nodes.size()},
                           {"min_edge", h.params.split_elements ? h.meshes.min_edge : 0.0},
                           {"element_passes", h.progress.element_passes},
                           {"elements_marked", h.progress.split_marks},
                           {"closed_scene", h.progress.closed},
                           // Refinement led by the camera (render and trace, unless --view-independent).
                           {"view_led", !h.view.seen.empty()},
                           {"final_gather_evaluations", h.progress.gather_evaluations},
                           // Diffuse light passed on by mirrors and glass (D S+ D).
                           {"specular_passes", h.progress.specular_passes},
                           {"specular_shot_fraction", h.progress.specular_shot_fraction},
                           {"warning", h.progress.warning}};
    out["power"] = {{"emitted", to_json(rgb(h.sources.emitted_power / 3.0))}};
    return out;
  }
  const power_balance& pb = progressive->balance;
  out["method"] = name_of(settings.form_factors.method);
  out["power_balance_error"] = balance_error(pb);
  out["power"] = {{"emitted", to_json(pb.emitted)},
                  {"received", to_json(pb.received)},
                  {"shot", to_json(pb.shot)},
                  {"unshot", to_json(pb.unshot)},
                  {"refined", to_json(pb.refined)}};
  return out;
}

bool start_command_solve(const scene& s, const solver_settings& settings, solve_setup& out) {
  std::string error;
  const bool started = start_solve(s, settings, out, error);
  setup_finished();
  if (started) return true;
  std::fprintf(stderr, "error: %s: %s\n", s.source.c_str(), error.c_str());
  return false;
}

void warn_about_mesh(const scene& s, const patch_mesh& mesh) {
  if (mesh.nonmanifold_faces)
    std::fprintf(stderr, "warning: %s: %zu non-manifold face(s) kept with vertices of their own\n", s.source.c_str(),
                 mesh.nonmanifold_faces);
  if (mesh.uncut_overlaps)
    std::fprintf(stderr,
                 "warning: %s: %zu coplanar overlap(s) or contact(s) could not be cut out of the surface behind\n",
                 s.source.c_str(), mesh.uncut_overlaps);
}

void warn_about_solve(const scene& s, const radiosity_solver& solver) {
  const hierarchical_solver* h = hierarchical_of(solver);
  if (!h) return;
  if (!h->progress.warning.empty())
    std::fprintf(stderr, "warning: %s: %s\n", s.source.c_str(), h->progress.warning.c_str());
  if (h->progress.links_cut_short)
    std::fprintf(stderr,
                 "warning: %s: --time ran out during a link refinement (%zu links): the solution keeps coarser "
                 "links where it had not reached\n",
                 s.source.c_str(), h->hierarchy.links.size());
}

bool write_stats(const std::string& path, const nlohmann::json& stats, std::string& error) {
  return write_file(path, stats.dump(2) + "\n", error);
}

}  // namespace bounce
