#include "viewer/error_tracker.h"

#include <cstdio>

namespace bounce {

struct error_tracker::job {
  std::uint64_t run = 0;
  std::shared_ptr<const patch_mesh> mesh;
  std::shared_ptr<const radiosity_snapshot> solution;
  bool converged = false;
  std::string setting;
};

error_tracker::error_tracker() = default;

error_tracker::~error_tracker() {
  {
    const std::lock_guard lock(mutex_);
    if (progress_) progress_->cancel = true;
  }
  jobs_.wait_idle();
}

void error_tracker::compute_reference(std::shared_ptr<const scene> source, const camera& view, int size, int spp) {
  camera request = view;
  request.width = request.height = size;
  auto progress = std::make_shared<trace_progress>();
  {
    const std::lock_guard lock(mutex_);
    if (progress_) progress_->cancel = true;  // a reference still being traced is replaced
    progress_ = progress;
  }
  jobs_.post([this, request, source, spp, progress] { trace_reference(request, source, spp, progress); });
}

void error_tracker::cancel_reference() {
  const std::lock_guard lock(mutex_);
  if (progress_) progress_->cancel = true;
}

void error_tracker::observe(const worker_view& view, const std::string& setting) {
  if (!view.solution || !view.mesh) return;
  {
    const std::lock_guard lock(mutex_);
    const std::uint64_t version = view.solution->version;
    if (view.run != worker_run_) {
      history_.clear();  // a new mesh or a restart: a new run
      pending_.reset();
      ++run_;
      worker_run_ = view.run;
      last_version_ = 0;
      queued_version_ = ~0ull;
    }
    if (version != last_version_) run_recorded_ = false;
    last_version_ = version;
    if (view.converged && !run_recorded_) {
      runs_[setting] = {view.solution->stats.seconds, view.solution->stats.remaining, not_measured};
      run_recorded_ = true;
    }
    // Each solution once; a new reference measures the current one again.
    // (again when the same solution turns out to be the converged one).
    if (judge_ && view.source == reference_source_ &&
        (version != queued_version_ || (view.converged && !queued_converged_))) {
      pending_ = std::make_shared<job>(job{run_, view.mesh, view.solution, view.converged, setting});
      queued_version_ = version;
      queued_converged_ = view.converged;
      if (!measure_posted_) {
        measure_posted_ = true;
        jobs_.post([this] { measure(); });
      }
    }
  }
}

error_status error_tracker::status(const std::string& setting) const {
  const std::lock_guard lock(mutex_);
  error_status s;
  s.computing = computing_;
  const long total = progress_ ? progress_->pixels_total.load() : 0;
  s.progress = total > 0 ? std::min(1.0, double(progress_->pixels_done) / double(total)) : 0.0;
  s.ready = judge_ != nullptr;
  s.summary = summary_;
  s.history = history_;
  if (const auto it = runs_.find(setting); it != runs_.end()) s.last = it->second;
  return s;
}

void error_tracker::trace_reference(camera request, std::shared_ptr<const scene> source, int spp,
                                    std::shared_ptr<trace_progress> progress) {
  if (progress->cancel) return;  // replaced before it started
  std::string before;            // what the panel said, back if this one is cancelled
  {
    const std::lock_guard lock(mutex_);
    computing_ = true;
    before = summary_;
    char line[160];
    std::snprintf(line, sizeof line, "path tracing the reference: %dx%d, %d spp", request.width, request.height, spp);
    summary_ = line;
  }
  trace_params params;
  params.method = integrator::path;
  params.spp = spp;
  trace_stats stats;
  bench_truth truth;
  truth.picture = trace_image(*source, request, ray_scene(*source), nullptr, params, progress.get(), &stats);
  truth.exclude_above = emitter_threshold(*source);
  // The judge refers to its scene: whoever holds the judge holds the scene.
  struct scene_and_judge {
    scene_and_judge(std::shared_ptr<const scene> s, const camera& view, const bench_truth& truth)
        : source(std::move(s)), judge(*source, view, truth) {}
    std::shared_ptr<const scene> source;
    picture_judge judge;
  };
  std::shared_ptr<const picture_judge> judge;
  if (!stats.cancelled) {
    auto both = std::make_shared<scene_and_judge>(source, request, truth);
    judge = std::shared_ptr<const picture_judge>(both, &both->judge);
  }
  const std::lock_guard lock(mutex_);
  computing_ = false;
  if (!judge) {
    // Cancelled: the reference before it (or none) stands; a replacement says its own.
    if (progress == progress_) summary_ = judge_ ? before : "reference cancelled: press 'Reference' to path trace one";
    return;
  }
  judge_ = judge;
  reference_source_ = source;
  queued_version_ = ~0ull;
  history_.clear();
  char line[160];
  std::snprintf(line, sizeof line, "reference: %dx%d path traced, %d spp, %.1f s; error = relative RMSE, 4x4 blocks",
                request.width, request.height, spp, stats.seconds);
  summary_ = line;
}

// Measures the newest solution queued (older ones queued meanwhile were
// replaced: measuring never holds the solver up).
void error_tracker::measure() {
  std::unique_lock lock(mutex_);
  measure_posted_ = false;
  if (!pending_ || !judge_) return;
  const std::shared_ptr<const job> work = std::move(pending_);
  const std::shared_ptr<const picture_judge> judge = judge_;
  lock.unlock();
  const double error =
      judge->judge_solution(*work->mesh, work->solution->radiosity, {}, diffuse_source::radiosity).error;
  lock.lock();
  if (judge != judge_ || work->run != run_) return;  // a new reference or a new run arrived meanwhile
  if (history_.empty() || history_.back().seconds != work->solution->stats.seconds)
    history_.push_back({work->solution->stats.seconds, error});
  if (work->converged) {
    if (auto it = runs_.find(work->setting); it != runs_.end() && it->second.seconds == work->solution->stats.seconds)
      it->second.error = error;
  }
}

}  // namespace bounce
