#include "measure/picture_judge.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "image/image_metrics.h"
#include "measure/run_clock.h"
#include "trace/radiosity_field.h"

namespace bounce {

picture_judge::picture_judge(const scene& s, const camera& view, const bench_truth& truth,
                             std::shared_ptr<const ray_scene> rays)
    : scene_(s),
      view_(view),
      downsample_(truth.downsample),
      still_spp_(truth.still_spp),
      rays_(rays ? std::move(rays) : std::make_shared<const ray_scene>(s)) {
  image reference = truth.picture;
  exclude_pixels(reference, bright_pixels(reference, truth.exclude_above), 1);
  reference_ = downsample(reference, downsample_);
  camera at_size = view;
  at_size.width = reference.width;
  at_size.height = reference.height;
  material_ = material_per_pixel(s, at_size, *rays_);
  full_reference_ = std::move(reference);
}

picture_judge::verdict picture_judge::judge(const image& picture) const {
  const image small = downsample(picture, downsample_);
  verdict v;
  v.error = relative_rmse(small, reference_);
  v.max_error = max_relative_error(small, reference_);
  v.surfaces = surface_means(picture, full_reference_, material_, scene_);
  return v;
}

picture_judge::verdict picture_judge::judge_solution(const patch_mesh& mesh, std::span<const rgb> radiosity,
                                                     std::span<const rgb> direct, diffuse_source source) const {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  radiosity_field field(mesh, radiosity, direct);
  trace_params params;
  params.spp = still_spp_;
  params.diffuse = source;
  verdict v = judge(trace_image(scene_, view_, *rays_, &field, params));
  v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  v.cpu_seconds = cpu_seconds() - c0;
  return v;
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
  return path_reference(s, s.view, ray_scene(s), spp, seed);
}

image path_reference(const scene& s, const camera& view, const ray_scene& rays, int spp, std::uint64_t seed) {
  trace_params params;
  params.method = integrator::path;
  params.spp = spp;
  params.seed = seed;
  return trace_image(s, view, rays, nullptr, params);
}

}  // namespace bounce
