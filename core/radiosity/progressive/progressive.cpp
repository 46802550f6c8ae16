#include "radiosity/progressive/progressive.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "radiosity/transfer/mirror_images.h"
#include "radiosity/transfer/point_lights.h"

namespace bounce {
namespace {

// Adds what the vertices received (delta per vertex) to every element's
// unshot radiosity, a third from each vertex; returns the power added.
rgb spread_to_elements(progressive_state& state, const std::vector<rgb>& delta) {
  const patch_mesh& mesh = *state.mesh;
  rgb power(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const rgb mean = element_mean(mesh, delta, e);
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
    power += element_mean(mesh, delta, e) * mesh.element_areas[e];
  }
  return power;
}

bool specular_on(const progressive_state& state) {
  return state.form_factors.mirrors || state.specular;
}

// A different, reproducible stream of specular paths for every shot.
std::uint64_t shot_seed(const progressive_state& state) {
  return state.params.form_factors.seed * 0x9E3779B97F4A7C15ull + state.stats.shots + 1;
}

// The mirrors and the specular elements of the state's mesh, when the
// scene has specular materials and the transfer is on.
void find_specular(progressive_state& state, const scene& s) {
  const form_factor_params& p = state.params.form_factors;
  state.form_factors.mirrors = nullptr;
  state.specular = nullptr;
  if (!p.specular_transfer || !has_specular_materials(s)) return;
  if (p.mirror_depth > 0) state.form_factors.mirrors = find_planar_mirrors(s, *state.mesh);
  if (p.specular_paths > 0) state.specular = find_specular_surfaces(s, *state.mesh, state.form_factors.mirrors.get());
}

// Irradiance from the specular paths of one source, added as reflected
// radiosity to `extra` and to state.traced.
void trace_source(progressive_state& state, const specular_source& source, std::vector<rgb>& extra) {
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

// What the punctual lights give by way of mirrors and glass, per vertex.
std::vector<rgb> specular_light_of_lights(progressive_state& state) {
  const patch_mesh& mesh = *state.mesh;
  std::vector<rgb> extra(mesh.vertex_count(), rgb(0.0));
  if (!specular_on(state) || state.source->lights.empty()) return extra;
  if (state.form_factors.mirrors)
    extra = mirrored_point_light_radiosity(*state.source, mesh, state.form_factors,
                                           state.params.form_factors.mirror_depth, state.stats.rays);
  if (state.specular)
    for (const punctual_light& light : state.source->lights) {
      specular_source source;
      source.light = &light;
      trace_source(state, source, extra);
    }
  return extra;
}

void update_fraction(progressive_state& state) {
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

void shoot_point_lights(progressive_state& state) {
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
void shoot_patch(progressive_state& state, std::size_t patch) {
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

std::unique_ptr<progressive_state> make_progressive_state(const scene& s, const patch_mesh& mesh,
                                                          const progressive_params& params) {
  check_mesh_contract(mesh);
  auto state = std::make_unique<progressive_state>();
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
  find_specular(*state, s);
  restart_progressive(*state);
  return state;
}

void restart_progressive(progressive_state& state) {
  const patch_mesh& mesh = *state.mesh;
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
    state.unshot[e] = element_mean(mesh, mesh.vertex_emission, e);
    state.balance.emitted += state.unshot[e] * mesh.element_areas[e];
  }
  state.unshot_emission = state.unshot;
  state.lights_shot = !has_lights_beyond_surfaces(*state.source);
  update_fraction(state);
  if (!state.lights_shot) state.stats.unshot_fraction = 1.0;  // the lights' power is still to come
}

bool step_progressive(progressive_state& state) {
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
  BOUNCE_CHECK_LE(balance_error(state.balance), 1e-6);
  return true;
}

bool all_emission_shot(const progressive_state& state) {
  return state.lights_shot && std::all_of(state.unshot_emission.begin(), state.unshot_emission.end(),
                                          [](const rgb& u) { return !(channel_sum(u) > 0.0); });
}

namespace {

bool same_triangle(const std::array<vec3, 3>& a, const std::array<vec3, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

}  // namespace

bool refine_progressive(progressive_state& state, std::span<const int> marked, double min_edge, std::string& error,
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

}  // namespace bounce
