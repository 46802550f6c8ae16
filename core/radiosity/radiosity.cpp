#include "radiosity/radiosity.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "base/check.h"
#include "radiosity/hierarchical/publication.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/point_lights.h"

namespace bounce {
namespace {

// Adds what the vertices received (delta per vertex) to every element's
// unshot radiosity, a third from each vertex; returns the power added.
rgb spread_to_elements(radiosity_state& state, const std::vector<rgb>& delta) {
  const patch_mesh& mesh = *state.mesh;
  rgb power(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    const rgb mean = (delta[t[0]] + delta[t[1]] + delta[t[2]]) / 3.0;
    state.unshot[e] += mean;
    power += mean * mesh.element_areas[e];
  }
  return power;
}

// Power of a per-vertex radiosity change, spread to the elements as
// spread_to_elements spreads it.
rgb element_power(const patch_mesh& mesh, const std::vector<rgb>& delta) {
  rgb power(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    power += (delta[t[0]] + delta[t[1]] + delta[t[2]]) / 3.0 * mesh.element_areas[e];
  }
  return power;
}

bool specular_on(const radiosity_state& state) {
  return state.form_factors.mirrors || state.specular;
}

// A different, reproducible stream of specular paths for every shot.
std::uint64_t shot_seed(const radiosity_state& state) {
  return state.params.form_factors.seed * 0x9E3779B97F4A7C15ull + state.stats.shots + 1;
}

// The mirrors and the specular elements of the state's mesh, when the
// scene has specular materials and the transfer is on.
void find_specular(radiosity_state& state, const scene& s) {
  const form_factor_params& p = state.params.form_factors;
  state.form_factors.mirrors = nullptr;
  state.specular = nullptr;
  if (!p.specular_transfer || !has_specular_materials(s)) return;
  if (p.mirror_depth > 0) state.form_factors.mirrors = find_planar_mirrors(s, *state.mesh);
  // The hierarchical solver finds its own specular elements (hierarchical.cpp).
  if (p.specular_paths > 0 && state.params.method == solver_method::progressive)
    state.specular = find_specular_surfaces(s, *state.mesh, state.form_factors.mirrors.get());
}

// Irradiance from the specular paths of one source, added as reflected
// radiosity to `extra` and to state.traced.
void trace_source(radiosity_state& state, const specular_source& source, std::vector<rgb>& extra) {
  const patch_mesh& mesh = *state.mesh;
  std::vector<rgb>& irradiance = state.traced_irradiance;
  std::fill(irradiance.begin(), irradiance.end(), rgb(0.0));
  state.stats.rays += trace_specular_paths(*state.source, state.form_factors, *state.specular, source, shot_seed(state),
                                           irradiance, state.specular_paths);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const rgb b = mesh.vertex_rho[v] * irradiance[v];
    extra[v] += b;
    state.traced[v] += b;
  }
}

// What the point lights give by way of mirrors and glass, per vertex.
std::vector<rgb> specular_light_of_lights(radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  std::vector<rgb> extra(mesh.vertex_count(), rgb(0.0));
  if (!specular_on(state) || state.source->lights.empty()) return extra;
  if (state.form_factors.mirrors)
    extra = mirrored_point_light_radiosity(*state.source, mesh, state.form_factors,
                                           state.params.form_factors.mirror_depth, state.stats.rays);
  if (state.specular)
    for (const point_light& light : state.source->lights) {
      specular_source source;
      source.position = light.position;
      source.intensity = light.intensity;
      trace_source(state, source, extra);
    }
  return extra;
}

void update_fraction(radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  // Refinement can make some unshot negative: the fraction counts its
  // magnitude, so that it cannot cancel the rest.
  rgb positive(0.0), negative(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    (channel_sum(state.unshot[e]) >= 0.0 ? positive : negative) += state.unshot[e] * mesh.element_areas[e];
  state.balance.unshot = positive + negative;  // summed afresh: a running difference would lose digits
  const double emitted = channel_sum(state.balance.emitted);
  state.stats.unshot_fraction = emitted > 0.0 ? (channel_sum(positive) - channel_sum(negative)) / emitted : 0.0;
}

void shoot_point_lights(radiosity_state& state) {
  std::uint64_t rays = 0;
  std::vector<rgb> delta = point_light_radiosity(*state.source, *state.mesh, state.form_factors, rays);
  for (std::size_t v = 0; v < delta.size(); ++v) {
    state.radiosity[v] += delta[v];
    state.direct[v] += delta[v];
  }
  // By way of mirrors and glass: not direct (the tracer's shadow rays do
  // not find it).
  const std::vector<rgb> extra = specular_light_of_lights(state);
  for (std::size_t v = 0; v < delta.size(); ++v) {
    state.radiosity[v] += extra[v];
    delta[v] += extra[v];
  }
  state.balance.specular += element_power(*state.mesh, extra);
  // Light from point lights enters the mesh here: it counts as emitted.
  state.balance.emitted += spread_to_elements(state, delta);
  state.stats.rays += rays;
  state.lights_shot = true;
}

// Shoots a patch: its elements' unshot radiosity, as the patch's
// area-weighted mean, through the patch's outline (Cohen 1986). With one
// element per patch this is element shooting exactly.
void shoot_patch(radiosity_state& state, std::size_t patch) {
  const patch_mesh& mesh = *state.mesh;
  state.stats.rays += form_factors_to_patch(state.form_factors, int(patch), state.scratch);
  rgb power(0.0), emission_power(0.0);
  for (int e : state.patch_elements[patch]) {
    power += state.unshot[e] * mesh.element_areas[e];
    emission_power += state.unshot_emission[e] * mesh.element_areas[e];
    state.unshot[e] = rgb(0.0);
    state.unshot_emission[e] = rgb(0.0);
  }
  state.balance.shot += power;
  const rgb shot = power / mesh.patch_areas[patch];
  const rgb shot_emission = emission_power / mesh.patch_areas[patch];
  const shooter from = patch_shooter(mesh, int(patch));
  // Its images in the planar mirrors: the same every time it shoots (and
  // after refinement: the mirrors are geometry), so their records follow
  // the patch's own in the log.
  const std::vector<shooter> images = state.form_factors.mirrors ? mirror_images(*state.form_factors.mirrors, from,
                                                                                 state.params.form_factors.mirror_depth)
                                                                 : std::vector<shooter>{};
  int& record = state.patch_log[patch];
  if (record < 0) {
    record = int(state.shot_log.size());
    state.shot_log.push_back({from});
    for (const shooter& image : images) state.shot_log.push_back({image});
  }
  state.shot_log[record].radiosity += shot;
  state.shot_log[record].emission += shot_emission;
  std::vector<rgb>& delta = state.received;  // reused from shot to shot: no allocation on the hot path
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double f = state.scratch[v];
    delta[v] = mesh.vertex_rho[v] * (f * shot);
    state.radiosity[v] += delta[v];
    state.direct[v] += mesh.vertex_rho[v] * (f * shot_emission);
  }
  if (specular_on(state)) {
    // By way of mirrors and glass: received like the rest, never direct.
    std::vector<rgb>& extra = state.specular_received;
    std::fill(extra.begin(), extra.end(), rgb(0.0));
    for (std::size_t i = 0; i < images.size(); ++i) {
      const rgb seen = images[i].through.kr * shot;
      state.stats.rays += form_factors_by_rays(state.form_factors, images[i], {}, state.scratch);
      state.shot_log[std::size_t(record) + 1 + i].radiosity += seen;
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) extra[v] += mesh.vertex_rho[v] * (state.scratch[v] * seen);
    }
    if (state.specular) {
      specular_source source;
      source.from = &from;
      source.radiosity = shot;
      trace_source(state, source, extra);
    }
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      delta[v] += extra[v];
      state.radiosity[v] += extra[v];
    }
    state.balance.specular += element_power(mesh, extra);
  }
  state.balance.received += spread_to_elements(state, delta);
}

}  // namespace

std::unique_ptr<radiosity_state> make_radiosity_state(const scene& s, const patch_mesh& mesh,
                                                      const radiosity_params& params) {
  // The mesher's contract: every element names three vertices of the mesh
  // and one of its patches.
  BOUNCE_CHECK(mesh.element_patches.size() == mesh.element_count());
  BOUNCE_CHECK(mesh.vertex_emission.size() == mesh.vertex_count());
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    BOUNCE_CHECK(t[0] >= 0 && t[1] >= 0 && t[2] >= 0);
    BOUNCE_CHECK(std::size_t(std::max({t[0], t[1], t[2]})) < mesh.vertex_count());
    BOUNCE_CHECK(std::size_t(mesh.element_patches[e]) < mesh.patch_count());
  }
  auto state = std::make_unique<radiosity_state>();
  state->mesh = &mesh;
  state->source = &s;
  state->params = params;
  state->form_factors = make_form_factor_context(mesh, params.form_factors);
  state->scratch.assign(mesh.vertex_count(), 0.0);
  state->received.assign(mesh.vertex_count(), rgb(0.0));
  state->patch_power.assign(mesh.patch_count(), 0.0);
  state->patch_elements.assign(mesh.patch_count(), {});
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    state->patch_elements[mesh.element_patches[e]].push_back(int(e));
  state->patch_log.assign(mesh.patch_count(), -1);
  find_specular(*state, s);  // the hierarchical solver takes the mirrors from the context
  if (params.method == solver_method::hierarchical)
    state->hierarchy = make_hierarchical_solver(s, mesh, state->form_factors, params.hierarchical);
  restart_radiosity(*state);
  return state;
}

namespace {

// The hierarchical solution at the vertices, its residual as the unshot
// radiosity of the elements, and its progress as statistics.
void publish_hierarchical(radiosity_state& state) {
  hierarchical_solver& h = *state.hierarchy;
  if (state.mesh != &h.mesh()) {  // elements were split (or a restart went back to the input mesh)
    state.mesh = &h.mesh();
    state.refined_mesh = h.meshes.refined;
    state.form_factors.mesh = state.mesh;  // the same geometry: the occlusion scene stays
    state.form_factors.vertex_areas.assign(state.mesh->vertex_count(), 0.0);
    for (std::size_t e = 0; e < state.mesh->element_count(); ++e)
      for (int k = 0; k < 3; ++k)
        state.form_factors.vertex_areas[state.mesh->elements[e][k]] += state.mesh->element_areas[e] / 3.0;
  }
  vertex_light light = publish_vertex_light(h);
  state.radiosity = std::move(light.radiosity);
  state.direct = std::move(light.direct);
  state.caustic = std::move(light.caustic);
  state.unshot = h.residual;
  state.stats.unshot_fraction = h.residual_fraction;
  // A step of the hierarchical solver (a block of iterations, or links
  // made or refined) counts as one shot: --max-shots and the frames
  // written during a solve count steps.
  state.stats.shots = h.progress.steps;
  state.stats.refinements = std::uint64_t(std::max(0, h.progress.refinements - 1));
  state.stats.rays = h.progress.rays;
  state.stats.links = h.hierarchy.links.size();
  state.stats.link_tolerance = h.progress.tolerance;
  state.stats.links_final = solution_final(h);
  state.balance = {};
  state.balance.emitted = rgb(h.sources.emitted_power / 3.0);
}

}  // namespace

void restart_radiosity(radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  if (state.hierarchy) {
    restart_hierarchical(*state.hierarchy);
    state.stats = {};
    publish_hierarchical(state);
    state.stats.unshot_fraction = 1.0;
    state.lights_shot = false;  // until the first links have carried the direct light
    return;
  }
  state.radiosity = mesh.vertex_emission;
  state.direct.assign(mesh.vertex_count(), rgb(0.0));
  state.traced.assign(mesh.vertex_count(), rgb(0.0));
  state.specular_received.assign(mesh.vertex_count(), rgb(0.0));
  state.traced_irradiance.assign(mesh.vertex_count(), rgb(0.0));
  state.specular_paths = {};
  state.unshot.assign(mesh.element_count(), rgb(0.0));
  state.balance = {};
  state.stats = {};
  state.shot_log.clear();
  std::fill(state.patch_log.begin(), state.patch_log.end(), -1);
  state.adaptive = {};
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    state.unshot[e] = (mesh.vertex_emission[t[0]] + mesh.vertex_emission[t[1]] + mesh.vertex_emission[t[2]]) / 3.0;
    state.balance.emitted += state.unshot[e] * mesh.element_areas[e];
  }
  state.unshot_emission = state.unshot;
  state.lights_shot = !has_lights_beyond_surfaces(*state.source);
  update_fraction(state);
  if (!state.lights_shot) state.stats.unshot_fraction = 1.0;  // the lights' power is still to come
}

bool step_radiosity(radiosity_state& state) {
  const auto start = std::chrono::steady_clock::now();
  if (state.hierarchy) {
    if (!step_hierarchical(*state.hierarchy, state.params.hierarchical.refine_below)) return false;
    publish_hierarchical(state);
    state.lights_shot = true;
    state.stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
  }
  if (!state.lights_shot) {
    shoot_point_lights(state);
    ++state.stats.shots;
  } else if (refinement_due(state)) {
    if (refine_pass(state)) ++state.stats.refinements;
  } else {
    // The patch with the most unshot power shoots next. Refinement can
    // leave negative unshot power (a shadow the coarse mesh had lit): it is
    // shot like any other, by magnitude.
    const patch_mesh& mesh = *state.mesh;
    std::vector<double>& power = state.patch_power;
    std::fill(power.begin(), power.end(), 0.0);
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
      power[mesh.element_patches[e]] += channel_sum(state.unshot[e]) * mesh.element_areas[e];
    const auto most =
        std::max_element(power.begin(), power.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    if (most == power.end() || !(std::abs(*most) > 0.0)) return false;
    shoot_patch(state, std::size_t(most - power.begin()));
    ++state.stats.shots;
  }
  update_fraction(state);
  // The power bookkeeping holds to round-off after every step (the
  // balance is kept as running sums: checking it costs nothing).
  BOUNCE_CHECK(balance_error(state.balance) <= 1e-6);
  state.stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

namespace {

bool same_triangle(const std::array<vec3, 3>& a, const std::array<vec3, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

}  // namespace

bool refine_radiosity(radiosity_state& state, std::span<const int> marked, double min_edge, std::string& error,
                      std::size_t* new_vertices) {
  const patch_mesh& old = *state.mesh;
  auto refined = std::make_shared<patch_mesh>(old);
  std::vector<int> origin;
  if (!refine_patch_mesh(*refined, marked, min_edge, origin, error)) return false;
  const patch_mesh& mesh = *refined;
  const std::size_t old_vertices = old.vertex_count();
  if (new_vertices) *new_vertices = mesh.vertex_count() - old_vertices;

  form_factor_context context = make_form_factor_context(mesh, state.params.form_factors);
  // The same mirrors (geometry, in the same order: the shot log's images
  // name them), their elements renumbered; the specular elements anew.
  std::shared_ptr<const specular_surfaces> specular;
  if (state.form_factors.mirrors) {
    auto mirrors = std::make_shared<mirror_set>(*state.form_factors.mirrors);
    mirrors->element_mirror.resize(mesh.element_count());
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
      mirrors->element_mirror[e] = state.form_factors.mirrors->element_mirror[std::size_t(origin[e])];
    context.mirrors = std::move(mirrors);
  }
  if (state.specular) specular = find_specular_surfaces(*state.source, mesh, context.mirrors.get());
  // New vertices gather what every shooter has shot so far: the very sum
  // that the shots would have added had the vertex been there all along.
  std::vector<int> added;
  for (std::size_t v = old_vertices; v < mesh.vertex_count(); ++v) added.push_back(int(v));
  std::vector<rgb> radiosity = std::move(state.radiosity), direct = std::move(state.direct);
  radiosity.resize(mesh.vertex_count(), rgb(0.0));
  direct.resize(mesh.vertex_count(), rgb(0.0));
  std::vector<rgb> gathered(added.size(), rgb(0.0)), gathered_direct(added.size(), rgb(0.0));
  std::vector<double> f(added.size());
  for (const shot_record& record : state.shot_log) {
    state.stats.rays += form_factors_by_rays(context, record.from, added, f);
    for (std::size_t i = 0; i < added.size(); ++i) {
      gathered[i] += f[i] * record.radiosity;
      gathered_direct[i] += f[i] * record.emission;
    }
  }
  std::vector<rgb> lights, mirrored;
  if (has_lights_beyond_surfaces(*state.source) && state.lights_shot) {
    std::uint64_t rays = 0;
    lights = point_light_radiosity(*state.source, mesh, context, rays, old_vertices);
    if (context.mirrors)
      mirrored = mirrored_point_light_radiosity(*state.source, mesh, context, state.params.form_factors.mirror_depth,
                                                rays, old_vertices);
    state.stats.rays += rays;
  }
  // What the specular paths brought cannot be gathered again: new vertices
  // take it interpolated over the element they were made in.
  std::vector<rgb> traced = std::move(state.traced);
  traced.resize(mesh.vertex_count(), rgb(0.0));
  std::vector<std::uint8_t> done(mesh.vertex_count(), 0);
  for (std::size_t e = 0; e < mesh.element_count() && state.specular; ++e)
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = std::size_t(mesh.elements[e][k]);
      if (v < old_vertices || done[v]) continue;
      done[v] = 1;
      const int o = origin[e];
      const vec3 b = barycentric(old, o, mesh.positions[v]);
      const glm::ivec3 t = old.elements[std::size_t(o)];
      traced[v] = b[0] * traced[t[0]] + b[1] * traced[t[1]] + b[2] * traced[t[2]];
    }
  for (std::size_t i = 0; i < added.size(); ++i) {
    const int v = added[i];
    const rgb light = lights.empty() ? rgb(0.0) : lights[v];
    const rgb specular_light = (mirrored.empty() ? rgb(0.0) : mirrored[v]) + traced[v];
    radiosity[v] = mesh.vertex_emission[v] + mesh.vertex_rho[v] * gathered[i] + light + specular_light;
    direct[v] = mesh.vertex_rho[v] * gathered_direct[i] + light;
  }

  // Each element keeps what its origin had shot (S), so its unshot moves
  // by the change in its vertices' mean: U = M B - S holds on the new mesh.
  std::vector<rgb> unshot(mesh.element_count()), unshot_emission(mesh.element_count());
  rgb before(0.0), after(0.0);
  for (std::size_t e = 0; e < old.element_count(); ++e) before += state.unshot[e] * old.element_areas[e];
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int o = origin[e];
    unshot[e] = state.unshot[o] + element_mean(mesh, radiosity, e) - element_mean(old, radiosity, o);
    unshot_emission[e] = state.unshot_emission[o];  // emission is uniform over an element
    after += unshot[e] * mesh.element_areas[e];
  }

  // A patch whose outline changed (a single-element patch that split) is a
  // new shooter: its old record stays in the log for the vertices to come.
  std::vector<int> patch_log(mesh.patch_count(), -1);
  for (std::size_t p = 0; p < old.patch_count(); ++p)
    if (same_triangle(old.patch_corners[p], mesh.patch_corners[p])) patch_log[p] = state.patch_log[p];

  state.refined_mesh = refined;
  state.mesh = refined.get();
  state.form_factors = std::move(context);
  state.radiosity = std::move(radiosity);
  state.direct = std::move(direct);
  state.traced = std::move(traced);
  state.specular = std::move(specular);
  state.specular_received.assign(mesh.vertex_count(), rgb(0.0));
  state.traced_irradiance.assign(mesh.vertex_count(), rgb(0.0));
  state.unshot = std::move(unshot);
  state.unshot_emission = std::move(unshot_emission);
  state.patch_log = std::move(patch_log);
  state.balance.refined += after - before;
  state.scratch.assign(mesh.vertex_count(), 0.0);
  state.received.assign(mesh.vertex_count(), rgb(0.0));
  state.patch_power.assign(mesh.patch_count(), 0.0);
  state.patch_elements.assign(mesh.patch_count(), {});
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    state.patch_elements[mesh.element_patches[e]].push_back(int(e));
  update_fraction(state);
  if (!state.lights_shot) state.stats.unshot_fraction = 1.0;
  return true;
}

double balance_error(const power_balance& b) {
  const double in = channel_sum(b.emitted + b.received);
  return in > 0.0 ? std::abs(channel_sum(b.emitted + b.received + b.refined - b.shot - b.unshot)) / in : 0.0;
}

rgb ambient_radiosity(const radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  rgb reflectance(0.0), unshot(0.0);
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    const rgb rho = (mesh.vertex_rho[t[0]] + mesh.vertex_rho[t[1]] + mesh.vertex_rho[t[2]]) / 3.0;
    reflectance += rho * mesh.element_areas[e];
    unshot += state.unshot[e] * mesh.element_areas[e];
    area += mesh.element_areas[e];
  }
  if (!(area > 0.0)) return rgb(0.0);
  // Interreflection factor 1 + rho + rho^2 + ... of the mean reflectance.
  const rgb mean_rho = reflectance / area;
  return unshot / area / (rgb(1.0) - mean_rho);
}

rgb mean_indirect_irradiance(const radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  rgb sum(0.0);
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    rgb irradiance(0.0);
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.elements[e][k];
      const rgb indirect = state.radiosity[v] - mesh.vertex_emission[v] - state.direct[v];
      for (int c = 0; c < 3; ++c)
        if (mesh.vertex_rho[v][c] > 0.0) irradiance[c] += indirect[c] / mesh.vertex_rho[v][c] / 3.0;
    }
    sum += irradiance * mesh.element_areas[e];
    area += mesh.element_areas[e];
  }
  return area > 0.0 ? sum / area : rgb(0.0);
}

std::shared_ptr<const radiosity_snapshot> make_snapshot(const radiosity_state& state) {
  const patch_mesh& mesh = *state.mesh;
  auto snap = std::make_shared<radiosity_snapshot>();
  snap->version = state.stats.shots + state.stats.refinements;
  snap->stats = state.stats;
  snap->ambient = ambient_radiosity(state);
  snap->radiosity = state.radiosity;
  snap->direct = state.direct;
  snap->caustic = state.caustic;
  std::vector<rgb> sum(mesh.vertex_count(), rgb(0.0));
  std::vector<int> count(mesh.vertex_count(), 0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      sum[mesh.elements[e][k]] += state.unshot[e];
      ++count[mesh.elements[e][k]];
    }
  snap->unshot_vertex.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    snap->unshot_vertex[v] = count[v] ? sum[v] / double(count[v]) : rgb(0.0);
  return snap;
}

}  // namespace bounce
