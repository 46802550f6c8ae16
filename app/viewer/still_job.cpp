#include "still_job.h"

#include <cstdio>

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
  const long total = progress_->pixels_total;
  return total > 0 ? std::min(1.0, double(progress_->pixels_done) / double(total)) : 0.0;
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
      field = std::make_unique<radiosity_field>(*mesh, solution->radiosity, solution->direct);
    } else if (p.method == integrator::whitted) {
      p.diffuse = diffuse_source::ambient;
    }
    auto out = std::make_shared<still_result>();
    out->source = source;
    out->picture = trace_image(*source, view, rays, field.get(), p, progress.get(), &out->stats);
    if (!out->stats.cancelled) {
      const trace_stats& st = out->stats;
      char line[256];
      std::snprintf(
          line, sizeof line, "%dx%d, %d spp%s: %.2f s, %.2f Mrays/s", view.width, view.height, p.spp,
          p.method == integrator::path ? " path traced" : "", st.seconds,
          st.seconds > 0 ? double(st.primary_rays + st.shadow_rays + st.secondary_rays) / st.seconds * 1e-6 : 0.0);
      out->summary = line;
      const std::lock_guard lock(mutex_);
      out->version = ++finished_;
      result_ = std::move(out);
    }
  });
}

}  // namespace bounce
