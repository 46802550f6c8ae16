#include "viewer/rest_refiner.h"

#include <algorithm>
#include <thread>

#include <tbb/task_arena.h>

#include "image/pass_blend.h"
#include "trace/radiosity_field.h"

namespace bounce {

rest_refiner::~rest_refiner() {
  stop();
  jobs_.wait_idle();
}

void rest_refiner::stop() {
  run_ = 0;
  latest_ = latest_ + 1;  // every run started before is now stale
  const std::lock_guard lock(mutex_);
  if (progress_) progress_->cancel = true;
  picture_.reset();
}

std::shared_ptr<const refined_picture> rest_refiner::picture() const {
  const std::lock_guard lock(mutex_);
  return picture_ && picture_->run == run_ ? picture_ : nullptr;
}

void rest_refiner::start(std::shared_ptr<const scene> source, const camera& view,
                         std::shared_ptr<const patch_mesh> mesh, std::shared_ptr<const radiosity_snapshot> solution,
                         image live, int samples_per_pass, int max_passes) {
  stop();
  const std::uint64_t run = latest_ = latest_ + 1;
  run_ = run;
  if (live.width != view.width || live.height != view.height) live = image{};
  jobs_.post([this, run, source, view, mesh, solution, live = std::move(live), samples_per_pass, max_passes] {
    if (latest_ != run) return;  // dropped before it began
    // One core fewer than the machine has: the window keeps one to draw with.
    tbb::task_arena arena(std::max(1, int(std::thread::hardware_concurrency()) - 1));
    arena.execute(
        [&] { trace_passes(run, *source, view, mesh.get(), solution.get(), live, samples_per_pass, max_passes); });
  });
}

void rest_refiner::trace_passes(std::uint64_t run, const scene& source, const camera& view, const patch_mesh* mesh,
                                const radiosity_snapshot* solution, const image& live, int samples_per_pass,
                                int max_passes) {
  const ray_scene rays(source);
  std::unique_ptr<radiosity_field> field;
  if (mesh && solution && solution->radiosity.size() == mesh->vertex_count())
    field = std::make_unique<radiosity_field>(*mesh, solution->radiosity, solution->direct, solution->ambient,
                                              solution->caustic);
  trace_params p;
  p.spp = samples_per_pass;
  p.light_samples = 4;  // a pass is cheap; the passes average the shadows
  if (!field) p.diffuse = diffuse_source::ambient;
  pass_sums sums;
  for (int pass = 1; pass <= max_passes && latest_ == run; ++pass) {
    auto progress = std::make_shared<trace_progress>();
    {
      const std::lock_guard lock(mutex_);
      progress_ = progress;
    }
    p.seed = std::uint64_t(pass);  // new jitter and light samples every pass
    trace_stats stats;
    const image one = trace_image(source, view, rays, field.get(), p, progress.get(), &stats);
    if (stats.cancelled || latest_ != run) return;
    add_pass(sums, one);
    auto out = std::make_shared<refined_picture>();
    out->shown = blend_passes_with_live(live, sums);
    out->passes = pass;
    out->run = run;
    const std::lock_guard lock(mutex_);
    if (latest_ == run) picture_ = std::move(out);
  }
}

}  // namespace bounce
