#include "bench.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include "closed_forms.h"
#include "image_metrics.h"
#include "radiosity.h"
#include "radiosity_field.h"
#include "ray_scene.h"
#include "ray_tracer.h"
#include "reference_solver.h"

namespace bounce {
namespace {

using clock_type = std::chrono::steady_clock;
using std::numbers::pi;

double cpu_now() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// Wall and CPU time of a run with the measuring taken out, so that a point's
// time is what the method would have cost without the bench looking at it.
class run_clock {
 public:
  double wall() const { return std::chrono::duration<double>(clock_type::now() - start_).count() - excluded_wall_; }
  double cpu() const { return cpu_now() - cpu_start_ - excluded_cpu_; }
  template <typename work>
  void exclude(work&& w) {
    const auto t0 = clock_type::now();
    const double c0 = cpu_now();
    w();
    excluded_wall_ += std::chrono::duration<double>(clock_type::now() - t0).count();
    excluded_cpu_ += cpu_now() - c0;
  }

 private:
  clock_type::time_point start_ = clock_type::now();
  double cpu_start_ = cpu_now();
  double excluded_wall_ = 0.0, excluded_cpu_ = 0.0;
};

// Compares per-vertex solutions with the closed form.
struct vertex_judge {
  const scene& s;
  exact_kind kind;
  std::vector<rgb> exact;
  double exact_power = 0.0;
  const patch_mesh* exact_for = nullptr;  // adaptive meshing changes the mesh: the exact values follow
  std::size_t exact_vertices = 0;

  vertex_judge(const scene& source, exact_kind k) : s(source), kind(k) {}

  void judge(const patch_mesh& mesh, std::span<const rgb> radiosity, bench_point& p) {
    if (exact_for != &mesh || exact_vertices != mesh.vertex_count()) {  // (a new mesh may reuse an address)
      exact = exact_vertex_radiosity(kind, s, mesh);
      exact_power = channel_sum(exact_reflected_power(kind, s, mesh));
      exact_for = &mesh;
      exact_vertices = mesh.vertex_count();
    }
    const vertex_error e = vertex_relative_error(radiosity, exact);
    p.error = e.rmse;
    p.max_error = e.max;
    p.power_error = std::abs(channel_sum(reflected_power(mesh, radiosity)) / exact_power - 1.0);
  }
};

bool all_emission_shot(const radiosity_state& state) {
  if (!state.lights_shot) return false;
  return std::all_of(state.unshot_emission.begin(), state.unshot_emission.end(),
                     [](const rgb& u) { return u.r == 0.0 && u.g == 0.0 && u.b == 0.0; });
}

bench_result run_progressive(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  run_clock clock;
  patch_mesh mesh;
  if (!make_patch_mesh(s, mesher_params_for(setting.solver, s), mesh, result.error)) return result;
  auto state = make_radiosity_state(s, mesh, radiosity_params_for(setting.solver));
  result.setup_seconds = clock.wall();
  result.elements = mesh.element_count();
  result.vertices = mesh.vertex_count();
  result.patches = mesh.patch_count();

  std::unique_ptr<picture_judge> pictures;
  std::unique_ptr<vertex_judge> vertices;
  if (setting.measure_error) {
    clock.exclude([&] {
      if (truth.exact == exact_kind::none)
        pictures = std::make_unique<picture_judge>(s, truth);
      else
        vertices = std::make_unique<vertex_judge>(s, truth.exact);
    });
  }
  const std::string method(name_of(setting.solver.form_factors.method));
  result.curves.push_back({method, {}});
  if (pictures) result.curves.push_back({method + " + two-pass", {}});

  auto record = [&] {
    bench_point p;
    p.seconds = clock.wall();
    p.cpu_seconds = clock.cpu();
    p.shots = state->stats.shots;
    p.rays = state->stats.rays;
    p.unshot_fraction = state->stats.unshot_fraction;
    p.balance_error = balance_error(state->balance);
    p.elements = state->mesh->element_count();
    clock.exclude([&] {
      const patch_mesh& mesh = *state->mesh;  // refined, with adaptive meshing
      if (vertices) vertices->judge(mesh, state->radiosity, p);
      if (!pictures) return;
      bench_point two_pass = p;
      const auto view = pictures->judge_solution(mesh, state->radiosity, {}, diffuse_source::radiosity);
      p.error = view.error;
      p.max_error = view.max_error;
      const auto still = pictures->judge_solution(mesh, state->radiosity, state->direct, diffuse_source::traced_direct);
      two_pass.seconds += still.seconds;
      two_pass.cpu_seconds += still.cpu_seconds;
      two_pass.error = still.error;
      two_pass.max_error = still.max_error;
      result.curves[1].points.push_back(two_pass);
    });
    result.curves[0].points.push_back(p);
  };

  // Stops spaced by a factor in time, so that a run of any length gives a
  // few dozen points evenly on the log-log plot.
  constexpr double stop_spacing = 1.25;
  double next_stop = 0.0;
  bool more = true;
  while (more) {
    more = step_radiosity(*state);
    const double t = clock.wall();
    if (std::isnan(result.first_picture_seconds) && all_emission_shot(*state)) result.first_picture_seconds = t;
    const bool done = !more || stop_reached(*state, setting.solver.stop);
    if (done || t >= next_stop) {
      record();
      next_stop = std::max(t * stop_spacing, t + 1e-3);
    }
    if (done) break;
  }
  if (state->stats.shots > 0) result.seconds_per_shot = state->stats.seconds / double(state->stats.shots);
  result.elements = state->mesh->element_count();  // adaptive: the refined mesh's
  result.vertices = state->mesh->vertex_count();
  return result;
}

bench_result run_reference(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  run_clock clock;
  patch_mesh mesh;
  if (!make_patch_mesh(s, mesher_params_for(setting.solver, s), mesh, result.error)) return result;
  result.elements = mesh.element_count();
  result.vertices = mesh.vertex_count();
  result.patches = mesh.element_count();
  const double mesh_seconds = clock.wall();
  reference_params params;
  params.form_factors = setting.solver.form_factors;
  reference_solution solution;
  if (!solve_reference(s, mesh, params, solution, result.error)) return result;
  result.setup_seconds = mesh_seconds + solution.seconds_matrix;

  std::unique_ptr<picture_judge> pictures;
  std::unique_ptr<vertex_judge> vertices;
  if (setting.measure_error) {
    if (truth.exact == exact_kind::none)
      pictures = std::make_unique<picture_judge>(s, truth);
    else
      vertices = std::make_unique<vertex_judge>(s, truth.exact);
  }
  auto point = [&](const std::vector<rgb>& radiosity, double solve_seconds, double residual) {
    bench_point p;
    p.seconds = result.setup_seconds + solve_seconds;
    p.cpu_seconds = not_measured;  // one process runs both; the run's CPU total is reported
    p.rays = solution.rays;
    p.residual = residual;
    if (vertices) vertices->judge(mesh, radiosity, p);
    if (pictures) {
      const auto v = pictures->judge_solution(mesh, radiosity, {}, diffuse_source::radiosity);
      p.error = v.error;
      p.max_error = v.max_error;
    }
    return p;
  };
  result.curves.push_back({"reference-lu", {point(solution.radiosity, solution.seconds_lu, solution.residual)}});
  result.curves.push_back(
      {"gauss-seidel",
       {point(solution.radiosity_gauss_seidel, solution.seconds_gauss_seidel, solution.residual_gauss_seidel)}});
  return result;
}

bench_result run_path(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  if (truth.exact != exact_kind::none) {
    result.error = "the path tracer is measured on pictures; this scene is measured per vertex";
    return result;
  }
  run_clock clock;
  picture_judge pictures(s, truth);
  result.setup_seconds = clock.wall();  // the ray-tracing BVH
  const double setup_cpu = clock.cpu();
  result.curves.push_back({"path", {}});
  double spent = 0.0;
  for (int spp = 1; spp <= setting.path_max_spp && spent < setting.solver.stop.seconds; spp *= 2) {
    trace_params params;
    params.method = integrator::path;
    params.spp = spp;
    params.seed = 2;  // the reference is traced with seed 1: independent noise
    trace_stats stats;
    const double c0 = cpu_now();
    const image picture = trace_image(s, pictures.rays(), nullptr, params, nullptr, &stats);
    bench_point p;
    p.cpu_seconds = setup_cpu + cpu_now() - c0;  // each picture is its own run: set-up plus its trace
    p.seconds = result.setup_seconds + stats.seconds;
    p.rays = stats.primary_rays + stats.shadow_rays + stats.secondary_rays;
    const auto v = pictures.judge(picture);
    p.error = v.error;
    p.max_error = v.max_error;
    result.curves[0].points.push_back(p);
    spent += stats.seconds;
  }
  return result;
}

// Emitting polygons of the scene: (corners, exitance).
std::vector<std::pair<std::vector<vec3>, rgb>> emitting_polygons(const scene& s) {
  std::vector<std::pair<std::vector<vec3>, rgb>> out;
  for (const surface& surf : s.surfaces) {
    const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    if (!mesh) continue;
    for (const polygon_face& f : mesh->faces) {
      const rgb ke = s.materials[f.material].ke;
      if (channel_sum(ke) <= 0.0) continue;
      std::vector<vec3> corners;
      for (int i : f.position) corners.push_back(mesh->positions[i]);
      out.emplace_back(std::move(corners), pi * ke);
    }
  }
  return out;
}

double area_of(std::span<const vec3> polygon) {
  vec3 sum(0.0);
  for (std::size_t i = 0; i < polygon.size(); ++i) sum += glm::cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * glm::length(sum);
}

vec3 normal_of(std::span<const vec3> polygon) {
  return glm::normalize(glm::cross(polygon[1] - polygon[0], polygon[2] - polygon[0]));
}

}  // namespace

picture_judge::picture_judge(const scene& s, const bench_truth& truth)
    : scene_(s), downsample_(truth.downsample), still_spp_(truth.still_spp), rays_(s) {
  image reference = truth.picture;
  exclude_pixels(reference, bright_pixels(reference, truth.exclude_above), 1);
  reference_ = downsample(reference, downsample_);
}

picture_judge::verdict picture_judge::judge(const image& picture) const {
  const image small = downsample(picture, downsample_);
  return {relative_rmse(small, reference_), max_relative_error(small, reference_)};
}

picture_judge::verdict picture_judge::judge_solution(const patch_mesh& mesh, std::span<const rgb> radiosity,
                                                     std::span<const rgb> direct, diffuse_source source) const {
  const auto t0 = clock_type::now();
  const double c0 = cpu_now();
  radiosity_field field(mesh, radiosity, direct);
  trace_params params;
  params.spp = still_spp_;
  params.diffuse = source;
  verdict v = judge(trace_image(scene_, rays_, &field, params));
  v.seconds = std::chrono::duration<double>(clock_type::now() - t0).count();
  v.cpu_seconds = cpu_now() - c0;
  return v;
}

bench_result run_bench(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  switch (setting.kind) {
    case bench_solver::progressive:
      return run_progressive(s, setting, truth);
    case bench_solver::reference:
      return run_reference(s, setting, truth);
    case bench_solver::path_tracer:
      return run_path(s, setting, truth);
  }
  return {};
}

double emitter_threshold(const scene& s) {
  double dimmest = 0.0;
  for (const material& m : s.materials) {
    const double ke = std::max({m.ke.r, m.ke.g, m.ke.b});
    if (ke > 0.0) dimmest = dimmest > 0.0 ? std::min(dimmest, ke) : ke;
  }
  return dimmest > 0.0 ? 0.5 * dimmest : std::numeric_limits<double>::infinity();
}

image path_reference(const scene& s, int spp, std::uint64_t seed) {
  ray_scene rays(s);
  trace_params params;
  params.method = integrator::path;
  params.spp = spp;
  params.seed = seed;
  return trace_image(s, rays, nullptr, params);
}

std::vector<rgb> exact_vertex_radiosity(exact_kind kind, const scene& s, const patch_mesh& mesh) {
  std::vector<rgb> exact(mesh.vertex_count(), rgb(0.0));
  switch (kind) {
    case exact_kind::none:
      break;
    case exact_kind::furnace:
      for (std::size_t v = 0; v < exact.size(); ++v)
        exact[v] = mesh.vertex_emission[v] / (rgb(1.0) - mesh.vertex_rho[v]);
      break;
    case exact_kind::sphere_interior: {
      rgb emitted(0.0);
      for (std::size_t e = 0; e < mesh.element_count(); ++e)
        emitted += mesh.vertex_emission[mesh.elements[e][0]] * mesh.element_areas[e];
      const double area = total_area(mesh);
      for (std::size_t v = 0; v < exact.size(); ++v) {
        const rgb rho = mesh.vertex_rho[v];
        exact[v] = mesh.vertex_emission[v] + rho * emitted / ((rgb(1.0) - rho) * area);
      }
      break;
    }
    case exact_kind::emitter_receiver: {
      // At the receive point: the one-sided limit on a shared edge, where
      // the function is continuous but the polygon touches the point.
      const auto emitters = emitting_polygons(s);
      for (std::size_t v = 0; v < exact.size(); ++v) {
        rgb received(0.0);
        for (const auto& [corners, exitance] : emitters)
          received += exitance * point_polygon_form_factor(mesh.receive_points[v], mesh.normals[v], corners);
        exact[v] = mesh.vertex_emission[v] + mesh.vertex_rho[v] * received;
      }
      break;
    }
  }
  return exact;
}

rgb exact_reflected_power(exact_kind kind, const scene& s, const patch_mesh& mesh) {
  if (kind == exact_kind::furnace || kind == exact_kind::sphere_interior) {
    // The closed form is constant over every element: its integral is exact.
    return reflected_power(mesh, exact_vertex_radiosity(kind, s, mesh));
  }
  if (kind != exact_kind::emitter_receiver) return rgb(not_measured);
  // One emitting rectangle and one receiving rectangle, opposed or at
  // 90 degrees along a shared edge: power = rho E A_emitter F(emitter -> receiver).
  const auto emitters = emitting_polygons(s);
  std::optional<std::vector<vec3>> receiver;
  rgb rho(0.0);
  for (const surface& surf : s.surfaces) {
    const auto* m = std::get_if<polygon_mesh>(&surf.geometry);
    if (!m || m->faces.size() != 1 || channel_sum(s.materials[m->faces[0].material].rho) <= 0.0) continue;
    receiver.emplace();
    for (int i : m->faces[0].position) receiver->push_back(m->positions[i]);
    rho = s.materials[m->faces[0].material].rho;
  }
  if (emitters.size() != 1 || !receiver || receiver->size() != 4 || emitters[0].first.size() != 4)
    return rgb(not_measured);
  const auto& [emitter, exitance] = emitters[0];
  const double a = glm::length(emitter[1] - emitter[0]), b = glm::length(emitter[2] - emitter[1]);
  const vec3 ne = normal_of(emitter), nr = normal_of(*receiver);
  double f = not_measured;
  if (glm::dot(ne, nr) < -0.999) {
    f = parallel_rectangles(a, b, std::abs(glm::dot(nr, emitter[0] - (*receiver)[0])));
  } else if (std::abs(glm::dot(ne, nr)) < 1e-3) {
    // The shared edge is the emitter's edge lying in the receiver's plane.
    for (int i = 0; i < 4; ++i) {
      const vec3 p = emitter[i], q = emitter[(i + 1) % 4];
      if (std::abs(glm::dot(nr, p - (*receiver)[0])) < 1e-9 && std::abs(glm::dot(nr, q - (*receiver)[0])) < 1e-9) {
        const double l = glm::length(q - p);
        const double w = area_of(emitter) / l, h = area_of(*receiver) / l;
        f = perpendicular_rectangles(l, w, h);
      }
    }
  }
  return rho * exitance * area_of(emitter) * f;
}

rgb reflected_power(const patch_mesh& mesh, std::span<const rgb> radiosity) {
  rgb total(0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    rgb mean(0.0);
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.elements[e][i];
      mean += radiosity[v] - mesh.vertex_emission[v];
    }
    total += mean * (mesh.element_areas[e] / 3.0);
  }
  return total;
}

vertex_error vertex_relative_error(std::span<const rgb> test, std::span<const rgb> exact) {
  if (test.size() != exact.size()) return {not_measured, not_measured};
  double largest = 0.0, sum = 0.0;
  for (const rgb& c : exact) {
    largest = std::max({largest, std::abs(c.r), std::abs(c.g), std::abs(c.b)});
    sum += std::abs(c.r) + std::abs(c.g) + std::abs(c.b);
  }
  const double floor = 1e-6 * largest;
  const double mean = sum / (3.0 * double(std::max<std::size_t>(exact.size(), 1)));
  vertex_error e;
  double squares = 0.0;
  for (std::size_t v = 0; v < test.size(); ++v)
    for (int c = 0; c < 3; ++c) {
      const double d = test[v][c] - exact[v][c];
      squares += d * d;
      e.max = std::max(e.max, std::abs(d) / std::max(std::abs(exact[v][c]), floor));
    }
  if (!(mean > 0.0)) return {not_measured, not_measured};
  e.rmse = std::sqrt(squares / (3.0 * double(test.size()))) / mean;
  return e;
}

std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors) {
  std::vector<bool> front(seconds.size(), false);
  for (std::size_t i = 0; i < seconds.size(); ++i) {
    if (std::isnan(errors[i]) || std::isnan(seconds[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < seconds.size() && !dominated; ++j) {
      if (j == i || std::isnan(errors[j]) || std::isnan(seconds[j])) continue;
      dominated =
          seconds[j] <= seconds[i] && errors[j] <= errors[i] && (seconds[j] < seconds[i] || errors[j] < errors[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

double growth_exponent(std::span<const double> x, std::span<const double> y) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    n += 1;
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  return n >= 2 && d > 0.0 ? (n * sxy - sx * sy) / d : not_measured;
}

double time_to_error(const bench_curve& curve, double target) {
  const bench_point* previous = nullptr;
  for (const bench_point& p : curve.points) {
    if (std::isnan(p.error)) continue;
    if (p.error <= target) {
      if (!previous || previous->error <= 0.0 || p.error <= 0.0 || target <= 0.0) return p.seconds;
      const double u = (std::log(target) - std::log(previous->error)) / (std::log(p.error) - std::log(previous->error));
      return std::exp(std::log(previous->seconds) + u * (std::log(p.seconds) - std::log(previous->seconds)));
    }
    previous = &p;
  }
  return not_measured;
}

}  // namespace bounce
