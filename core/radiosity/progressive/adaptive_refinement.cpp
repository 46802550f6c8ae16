#include "radiosity/progressive/adaptive_refinement.h"

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "radiosity/progressive/progressive.h"

namespace bounce {
namespace {

// Area-weighted mean exitance of the emitted power over the whole mesh: the
// scale of "dark" for the absolute floor.
double mean_exitance(const progressive_state& state) {
  const double area = total_area(*state.mesh);
  return area > 0.0 ? channel_sum(state.balance.emitted) / area : 0.0;
}

std::vector<int> sorted_unique(std::vector<int> marks) {
  std::sort(marks.begin(), marks.end());
  marks.erase(std::unique(marks.begin(), marks.end()), marks.end());
  return marks;
}

}  // namespace

double resolved_min_edge(const adaptive_params& params, const patch_mesh& mesh) {
  return params.min_edge > 0.0 ? params.min_edge : default_min_edge(mesh.max_edge);
}

std::vector<int> gradient_marks(const progressive_state& state, const adaptive_params& params) {
  const patch_mesh& mesh = *state.mesh;
  const double min_edge = resolved_min_edge(params, mesh);
  const double floor = params.floor * mean_exitance(state);
  std::vector<int> marks;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    double lo = 1e300, hi = -1e300, mean = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double b = channel_sum(state.radiosity[t[k]]);
      lo = std::min(lo, b);
      hi = std::max(hi, b);
      mean += b / 3.0;
    }
    if (hi - lo > params.tolerance * std::max(mean, floor) && element_longest_edge(mesh, e) > min_edge)
      marks.push_back(int(e));
  }
  return marks;
}

std::vector<int> shadow_marks(progressive_state& state, const adaptive_params& params) {
  const patch_mesh& mesh = *state.mesh;
  const double min_edge = resolved_min_edge(params, mesh);
  const double floor = params.floor * mean_exitance(state);
  // The strong shooters: at least params.shadow_shooters of the strongest
  // one's shot power (an emitter meshed into many elements has many equal
  // shooters), the strongest max_shadow_shooters of them.
  std::vector<std::pair<double, const shot_record*>> strong;
  for (const shot_record& record : state.shot_log)
    strong.emplace_back(channel_sum(record.radiosity) * record.from.area, &record);
  std::sort(strong.begin(), strong.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  if (strong.size() > std::size_t(params.max_shadow_shooters)) strong.resize(std::size_t(params.max_shadow_shooters));
  std::vector<double> f(mesh.vertex_count());
  std::vector<std::uint8_t> seen(mesh.vertex_count());
  std::vector<int> marks;
  for (const auto& [power, entry] : strong) {
    if (!(power >= params.shadow_shooters * strong.front().first)) break;
    const shot_record& record = *entry;
    state.stats.rays += form_factors_by_rays(state.form_factors, record.from, {}, f, seen);
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      const glm::ivec3 t = mesh.elements[e];
      bool any_hidden = false, any_whole = false, any_partly = false;
      double strongest = 0.0, mean = 0.0;
      for (int k = 0; k < 3; ++k) {
        const int v = t[k];
        any_hidden |= seen[v] == hidden;
        any_whole |= seen[v] == seen_whole;
        any_partly |= seen[v] == seen_partly;
        strongest = std::max(strongest, channel_sum(mesh.vertex_rho[v] * (f[v] * record.radiosity)));
        mean += channel_sum(state.radiosity[v]) / 3.0;
      }
      // A shadow edge crosses the element, and the light it cuts matters.
      // (A vertex that sees the shooter partly lies in its penumbra.)
      const bool boundary = any_partly || (any_hidden && any_whole);
      if (boundary && strongest > params.tolerance * std::max(mean, floor) && element_longest_edge(mesh, e) > min_edge)
        marks.push_back(int(e));
    }
  }
  return sorted_unique(std::move(marks));
}

bool refinement_due(const progressive_state& state) {
  const adaptive_progress& progress = state.adaptive;
  if (!state.params.adaptive.enabled || progress.finished || !state.lights_shot) return false;
  if (progress.passes >= state.params.adaptive.max_passes) return false;
  // Every emitter must have shot: before that, the light is half there.
  if (!all_emission_shot(state)) return false;
  return state.stats.unshot_fraction <= progress.next_fraction;
}

bool refine_pass(progressive_state& state) {
  const auto start = std::chrono::steady_clock::now();
  const adaptive_params& params = state.params.adaptive;
  adaptive_progress& progress = state.adaptive;
  refinement_pass pass;
  pass.unshot_fraction = state.stats.unshot_fraction;
  pass.elements_before = state.mesh->element_count();
  std::vector<int> marks = gradient_marks(state, params);
  pass.gradient = marks.size();
  std::vector<int> shadow = shadow_marks(state, params);
  pass.shadow = shadow.size();
  marks.insert(marks.end(), shadow.begin(), shadow.end());
  marks = sorted_unique(std::move(marks));
  ++progress.passes;
  bool changed = false;
  if (marks.empty()) {
    progress.finished = true;
  } else if (!refine_progressive(state, marks, resolved_min_edge(params, *state.mesh), progress.error,
                                 &pass.new_vertices)) {
    progress.finished = true;  // the mesh limit: keep solving on the mesh we have
  } else {
    changed = true;
  }
  pass.elements_after = state.mesh->element_count();
  progress.next_fraction = state.stats.unshot_fraction / params.refine_every;
  pass.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.history.push_back(pass);
  return changed;
}

}  // namespace bounce
