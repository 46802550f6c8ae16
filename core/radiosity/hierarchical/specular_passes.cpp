#include "radiosity/hierarchical/specular_passes.h"

#include <algorithm>

namespace bounce {
namespace {

// The form-factor context on the input mesh, with its vertices' areas
// (which specular paths deposit over).
form_factor_context input_context(const hierarchical_solver& solver) {
  const patch_mesh& mesh = *solver.meshes.input;
  form_factor_context context = solver.context;
  context.mesh = &mesh;
  context.vertex_areas.assign(mesh.vertex_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) context.vertex_areas[std::size_t(mesh.elements[e][k])] += mesh.element_areas[e] / 3.0;
  return context;
}

// Per element of `mesh`, the mean of its vertices' values.
std::vector<rgb> vertex_to_element(const patch_mesh& mesh, const std::vector<rgb>& vertex) {
  std::vector<rgb> out(mesh.element_count());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) out[e] = element_mean(mesh, vertex, e);
  return out;
}

// The diffuse light that mirrors and glass pass on, per element of the
// input mesh: every patch radiating the area-weighted mean of its
// elements' reflected radiosity B - E, carried as specular_lamp_of
// carries the emitters'.
std::vector<rgb> passed_on_specular_light(hierarchical_solver& solver, std::uint64_t& rays) {
  const patch_mesh& mesh = solver.mesh();
  const patch_mesh& input = *solver.meshes.input;
  std::vector<rgb> reflected(input.patch_count(), rgb(0.0));
  std::vector<double> area(input.patch_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::size_t p = std::size_t(mesh.element_patches[e]);
    if (p >= reflected.size()) continue;
    reflected[p] += glm::max(solver.light.total[e] - solver.sources.emission[e], rgb(0.0)) * mesh.element_areas[e];
    area[p] += mesh.element_areas[e];
  }
  for (std::size_t p = 0; p < reflected.size(); ++p) reflected[p] = area[p] > 0.0 ? reflected[p] / area[p] : rgb(0.0);
  const std::shared_ptr<const specular_surfaces> surfaces = path_targets(solver);
  form_factor_context context = input_context(solver);
  // A quarter of the shadow rays and paths of a shot: every patch sends
  // light this way, and their noise averages out over the receivers.
  context.params.shadow_rays = std::max(1, context.params.shadow_rays / 4);
  context.params.specular_paths = std::max(1, context.params.specular_paths / 4);
  // Seeds apart from the emitters' paths, and from pass to pass.
  std::uint64_t seed = (solver.context.params.seed + 0x51ED27ull * std::uint64_t(solver.progress.specular_passes + 1)) *
                       0xD1B54A32D192ED03ull;
  return vertex_to_element(
      input, specular_light_from_patches(*solver.source, context, surfaces.get(), reflected, seed, rays,
                                         solver.progress.specular_ray_budget, &solver.progress.specular_shot_fraction,
                                         solver.hierarchy.chains.empty()));
}

}  // namespace

std::shared_ptr<const specular_surfaces> path_targets(const hierarchical_solver& solver) {
  return solver.context.params.specular_paths > 0
             ? find_specular_surfaces(*solver.source, *solver.meshes.input, solver.context.mirrors.get())
             : nullptr;
}

std::vector<rgb> specular_lamp_of(const hierarchical_solver& solver, std::uint64_t& rays) {
  const scene& s = *solver.source;
  const form_factor_params& p = solver.context.params;
  if (!p.specular_transfer || !has_specular_materials(s)) return {};
  const std::shared_ptr<const specular_surfaces> surfaces = path_targets(solver);
  if (!surfaces && !solver.context.mirrors) return {};
  const form_factor_context context = input_context(solver);
  return vertex_to_element(*solver.meshes.input, specular_light_from_sources(s, context, surfaces.get(), rays,
                                                                             solver.hierarchy.chains.empty(), false));
}

bool specular_passes_done(const hierarchical_solver& solver) {
  // With links through mirrors, the passes have only paths to carry.
  return solver.sources.specular_lamp.empty() || solver.progress.specular_passes >= solver.params.specular_bounces ||
         (!solver.hierarchy.chains.empty() && !solver.sources.has_path_targets);
}

void make_specular_pass(hierarchical_solver& solver) {
  if (solver.progress.specular_passes == 0)
    solver.progress.specular_ray_budget =
        std::max(solver.params.specular_min_rays,
                 std::uint64_t(solver.params.specular_ray_share * double(solver.progress.rays)));
  std::vector<rgb> light = passed_on_specular_light(solver, solver.progress.rays);
  for (std::size_t e = 0; e < light.size(); ++e) light[e] += solver.sources.specular_lamp_input[e];
  set_specular_lamp(solver, light);
  ++solver.progress.specular_passes;
}

void set_specular_lamp(hierarchical_solver& solver, const std::vector<rgb>& per_input) {
  element_sources& src = solver.sources;
  for (std::size_t e = 0; e < src.specular_lamp.size(); ++e) {
    const rgb next = per_input[std::size_t(solver.meshes.input_element[e])];
    src.lamp[e] += next - src.specular_lamp[e];
    src.specular_lamp[e] = next;
  }
}

}  // namespace bounce
