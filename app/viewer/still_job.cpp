#include "viewer/still_job.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace bounce {

still_job::~still_job() {
  cancel();
}

void still_job::cancel() {
  {
    const std::lock_guard lock(mutex_);
    if (progress_) progress_->cancel = true;
  }
  jobs_.wait_idle();
}

double still_job::progress() const {
  const std::lock_guard lock(mutex_);
  if (!progress_) return 0.0;
  auto ratio = [](double done, double total) { return total > 0 ? std::min(1.0, done / total) : 0.0; };
  const trace_progress& p = *progress_;
  switch (p.stage.load()) {
    case trace_stage::photons:
      return ratio(double(p.photons.photons_done), double(p.photons.photons_total));
    case trace_stage::cache:
      return ratio(double(p.cache_points_done), double(p.cache_points_total));
    case trace_stage::passes:
      return ratio(p.passes_done, p.passes_total);
    case trace_stage::pixels:
      break;
  }
  return ratio(double(p.pixels_done), double(p.pixels_total));
}

std::shared_ptr<const still_result> still_job::result() const {
  const std::lock_guard lock(mutex_);
  return result_;
}

void still_job::start(std::shared_ptr<const scene> source, const camera& view, std::shared_ptr<const patch_mesh> mesh,
                      std::shared_ptr<const radiosity_snapshot> solution, const trace_params& params) {
  cancel();
  auto progress = std::make_shared<trace_progress>();
  {
    const std::lock_guard lock(mutex_);
    progress_ = progress;
  }
  jobs_.post([this, progress, source, view, mesh, solution, params] {
    trace_params p = params;
    const ray_scene rays(*source);
    std::unique_ptr<radiosity_field> field;
    if (mesh && solution && solution->radiosity.size() == mesh->vertex_count()) {
      field = std::make_unique<radiosity_field>(*mesh, solution->radiosity, solution->direct, solution->ambient,
                                                solution->caustic);
    } else if (p.method != integrator::path) {
      // No solution yet: one-pass Whitted, with no ambient term.
      p.method = integrator::whitted;
      p.diffuse = diffuse_source::ambient;
    }
    auto summary = [&](const trace_stats& st, int passes) {
      const char* kind = p.method == integrator::path      ? " path traced"
                         : p.method == integrator::twopass ? " two-pass"
                         : p.method == integrator::ppm     ? " photon mapped"
                                                           : "";
      char line[256];
      std::snprintf(line, sizeof line, "%dx%d, %d spp%s", view.width, view.height, p.spp, kind);
      std::string text = line;
      if (p.method == integrator::ppm) {
        std::snprintf(line, sizeof line, ", %d of %d photon passes", passes, p.passes);
        text += line;
      }
      if (st.seconds > 0) {
        std::snprintf(
            line, sizeof line, ": %.2f s, %.2f Mrays/s", st.seconds,
            double(st.primary_rays + st.shadow_rays + st.secondary_rays + st.gather_rays) / st.seconds * 1e-6);
        text += line;
      }
      return text;
    };
    // Progressive photon mapping shows each pass's picture as it comes.
    progress->pass_done = [&](const image& picture, int passes) {
      auto out = std::make_shared<still_result>();
      out->source = source;
      out->picture = picture;
      out->summary = summary(out->stats, passes);
      const std::lock_guard lock(mutex_);
      out->version = ++finished_;
      result_ = std::move(out);
    };
    auto out = std::make_shared<still_result>();
    out->source = source;
    out->picture = trace_image(*source, view, rays, field.get(), p, progress.get(), &out->stats);
    if (!out->stats.cancelled) {
      out->summary = summary(out->stats, out->stats.passes);
      const std::lock_guard lock(mutex_);
      out->version = ++finished_;
      result_ = std::move(out);
    }
  });
}

}  // namespace bounce
