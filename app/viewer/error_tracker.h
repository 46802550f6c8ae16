// Error against time in the window: on request, a path-traced reference of
// the current camera is made in the background; from then on the solutions
// the solver publishes are measured against it on the same background
// thread (the newest one each time, so it never holds the solver up), and
// the panel plots the error beside the remaining power. It also remembers the
// time and error of the last finished run per solver setting. GL-free.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/background_worker.h"
#include "measure/bench.h"
#include "viewer/solver_worker.h"

namespace bounce {

struct error_point {
  double seconds;  // solver time of the solution
  double error;    // relative RMSE of its picture against the reference
};

struct last_run {
  double seconds = 0.0;         // solver time to the stopping criterion
  double remaining = 0.0;       // solver_stats::remaining
  double error = not_measured;  // against the reference, if there was one
};

struct error_status {
  bool computing = false;  // the reference is being path traced
  double progress = 0.0;   // 0..1
  bool ready = false;
  std::string summary;  // what the reference is, or why there is none
  std::vector<error_point> history;
  std::optional<last_run> last;  // of the setting asked about
};

class error_tracker {
 public:
  error_tracker();
  ~error_tracker();  // cancels and joins
  error_tracker(const error_tracker&) = delete;
  error_tracker& operator=(const error_tracker&) = delete;

  // Path traces a reference of `view` (size x size pixels, `spp` samples)
  // of this scene; measuring starts once it is ready.
  void compute_reference(std::shared_ptr<const scene> source, const camera& view, int size, int spp);
  // Stops the reference being traced, if any; a reference made before stays.
  void cancel_reference();

  // Called every frame with the newest view and the setting it was solved
  // with: queues the newest solution for measuring, restarts the history
  // when the solver restarts, and records finished runs under `setting`.
  void observe(const worker_view& view, const std::string& setting);

  error_status status(const std::string& setting) const;

 private:
  struct job;
  void trace_reference(camera request, std::shared_ptr<const scene> source, int spp,
                       std::shared_ptr<trace_progress> progress);
  void measure();

  mutable std::mutex mutex_;

  // Guarded by mutex_.
  std::shared_ptr<trace_progress> progress_;  // of the newest reference asked for; each has its own
  std::shared_ptr<const picture_judge> judge_;
  std::shared_ptr<const scene> reference_source_;  // solutions of this scene are measured
  bool computing_ = false;
  std::string summary_ = "no reference: press 'Reference' to path trace one";
  std::shared_ptr<const job> pending_;  // newest solution not yet measured
  std::vector<error_point> history_;
  std::uint64_t worker_run_ = 0, last_version_ = 0;  // the worker's run last seen, and its last solution
  std::uint64_t queued_version_ = ~0ull;             // the solution last queued for measuring
  std::map<std::string, last_run> runs_;
  bool run_recorded_ = false;
  bool queued_converged_ = false;  // whether the queued solution was queued as converged
  bool measure_posted_ = false;    // a measuring task is waiting: it takes the newest pending solution
  std::uint64_t run_ = 0;          // counts restarts and new meshes: a measurement of an older run is dropped

  background_worker jobs_;  // last: destroyed first, so no task outlives the members it uses
};

}  // namespace bounce
