// Speed against error: runs one solver setting on one scene and records its
// error at many points along the way (one run, not one run per stop), for
// `bounce bench`. GL-free; the error of a solution is measured against a
// closed form per vertex where one exists, otherwise through a picture of
// the solution against a path-traced reference picture.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "adaptive.h"
#include "form_factor.h"
#include "image.h"
#include "patch_mesh.h"
#include "ray_scene.h"
#include "ray_tracer.h"
#include "solver_settings.h"

namespace bounce {

inline constexpr double not_measured = std::numeric_limits<double>::quiet_NaN();

enum class bench_solver {
  progressive,  // shooting (Cohen 1988), error recorded at stops along the run
  reference,    // full matrix: LU and Gauss-Seidel, one point each
  path_tracer,  // the reference integrator itself, at doubling sample counts
};

struct bench_setting {
  bench_solver kind = bench_solver::progressive;
  // Mesh, form factors, adaptive meshing and the stop (progressive; the
  // path tracer stops at stop.seconds too).
  solver_settings solver = [] {
    solver_settings d;
    d.stop.unshot_fraction = 1e-3;
    d.stop.seconds = 10.0;
    return d;
  }();
  bool measure_error = true;  // false: timings only (the growth runs)
  int path_max_spp = 1 << 14;
};

// The closed forms of accuracy.md that a scene's solution is compared with.
enum class exact_kind {
  none,              // no closed form: compare pictures with a path-traced reference
  furnace,           // item 6: B = E / (1 - rho) everywhere
  sphere_interior,   // item 7: B_j = E_j + rho P_E / ((1 - rho) A)
  emitter_receiver,  // items 1-3: non-reflecting emitters over one reflecting polygon
};

// What errors are measured against. For exact_kind::none, `picture` is the
// path-traced reference of s.view (linear radiance) and the comparison is
// made after box-filtering `downsample` x `downsample` blocks, with the
// pixels that see an emitter (and their neighbours) left out: their edges'
// aliasing would otherwise decide the figure.
struct bench_truth {
  exact_kind exact = exact_kind::none;
  image picture;
  int downsample = 4;
  double exclude_above = 0.0;  // radiance above which a reference pixel counts as an emitter
  int still_spp = 4;           // samples per pixel of the pictures of a solution
};

struct bench_point {
  double seconds = 0.0;      // wall time from the loaded scene to this solution (measuring excluded)
  double cpu_seconds = 0.0;  // CPU time of all threads over the same span
  std::uint64_t shots = 0;
  std::uint64_t rays = 0;
  double unshot_fraction = not_measured;
  double error = not_measured;          // relative RMSE: per vertex (closed form) or over the picture
  double max_error = not_measured;      // largest relative error, same samples
  double power_error = not_measured;    // reflected power against the closed form, relative
  double balance_error = not_measured;  // progressive: |emitted + received - shot - unshot| / (emitted + received)
  double residual = not_measured;       // matrix solvers: max |(I - R K) B - b| / max |b|
  std::size_t elements = 0;             // elements of the mesh at this point (adaptive meshing grows it)
};

// One curve of the plot: a method/setting and its error over time.
struct bench_curve {
  std::string method;  // raycast, hemicube, reference-lu, gauss-seidel, path, and "+ two-pass" variants
  std::vector<bench_point> points;
};

struct bench_result {
  std::size_t elements = 0, vertices = 0, patches = 0;
  double setup_seconds = 0.0;                   // meshing, BVH and form-factor set-up
  double first_picture_seconds = not_measured;  // until every emitter has shot: direct light everywhere
  double seconds_per_shot = not_measured;
  std::vector<bench_curve> curves;
  std::string error;  // why the run could not be made (e.g. too large for the full matrix)
};

// Measures solutions of a scene through pictures of them against the
// truth's reference picture: both box-filtered, the emitters' pixels left
// out of both. The bench and the viewer's error plot both use it. The scene
// must outlive the judge.
class picture_judge {
 public:
  picture_judge(const scene& s, const bench_truth& truth);

  struct verdict {
    double error = not_measured, max_error = not_measured;
    double seconds = 0.0, cpu_seconds = 0.0;  // to make the picture (radiosity field + tracing)
  };
  verdict judge(const image& picture) const;
  // A still of the solution at the reference's size: all diffuse light from
  // it (diffuse_source::radiosity, what the Gouraud view shows) or direct
  // light by shadow rays and the rest from it (traced_direct: two-pass).
  verdict judge_solution(const patch_mesh& mesh, std::span<const rgb> radiosity, std::span<const rgb> direct,
                         diffuse_source source) const;
  const ray_scene& rays() const { return rays_; }

 private:
  const scene& scene_;
  int downsample_ = 4, still_spp_ = 4;
  ray_scene rays_;
  image reference_;
};

// Radiance above which a reference pixel counts as showing an emitter: half
// the dimmest emitting material's brightest channel (infinity: no emitters).
double emitter_threshold(const scene& s);

// Runs `setting` on `s` (whose view is the bench picture's camera and size).
bench_result run_bench(const scene& s, const bench_setting& setting, const bench_truth& truth);

// The path-traced reference picture of s.view: `spp` samples per pixel.
image path_reference(const scene& s, int spp, std::uint64_t seed);

// Per-vertex closed form of the scene (exact_kind != none).
std::vector<rgb> exact_vertex_radiosity(exact_kind kind, const scene& s, const patch_mesh& mesh);
// The total power the scene's surfaces reflect, from the closed form.
rgb exact_reflected_power(exact_kind kind, const scene& s, const patch_mesh& mesh);
// The same from a solution: sum over elements of area x (mean of the
// vertices' B - E), the integral of what the Gouraud view shows.
rgb reflected_power(const patch_mesh& mesh, std::span<const rgb> radiosity);

struct vertex_error {
  double rmse = 0.0;  // RMS difference over vertices and channels / mean of the exact values
  double max = 0.0;   // largest |difference| / exact, exact values below 1e-6 of the largest counted as that
};
// NaN for both when the sizes differ or the exact values are all zero:
// nothing to be relative to.
vertex_error vertex_relative_error(std::span<const rgb> test, std::span<const rgb> exact);

// A point (seconds, error) is on the Pareto front when no other point is
// at least as fast and at least as accurate, and strictly better in one.
// Returns one flag per point; points whose error was not measured are never
// on it.
std::vector<bool> pareto_front(std::span<const double> seconds, std::span<const double> errors);

// Least-squares slope of log(y) against log(x): the exponent of y ~ x^k.
double growth_exponent(std::span<const double> x, std::span<const double> y);

// The earliest time at which a curve's error is at or below `target`
// (linearly interpolated in log-log between stops; NaN if never).
double time_to_error(const bench_curve& curve, double target);

}  // namespace bounce
