// A ray-traced still made in the background while the window stays
// interactive: the panel starts it with the current camera and the latest
// radiosity solution, shows its progress, can cancel it, and shows the
// result. GL-free; the window uploads the finished image itself.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include "base/background_worker.h"
#include "image/image.h"
#include "mesh/patch_mesh.h"
#include "radiosity/solution.h"
#include "trace/ray_tracer.h"

namespace bounce {

struct still_result {
  std::uint64_t version = 0;            // increases with every finished still
  std::shared_ptr<const scene> source;  // the scene it shows
  image picture;                        // linear radiance
  trace_stats stats;
  std::string summary;  // one line for the panel: size, samples, time, rays
};

class still_job {
 public:
  still_job() = default;
  ~still_job();  // cancels and joins
  still_job(const still_job&) = delete;
  still_job& operator=(const still_job&) = delete;

  // Traces `view` of the scene with the solution of `mesh` (two-pass; with
  // no solution yet the still is one-pass with no ambient term). A still
  // already running is cancelled first.
  void start(std::shared_ptr<const scene> source, const camera& view, std::shared_ptr<const patch_mesh> mesh,
             std::shared_ptr<const radiosity_snapshot> solution, const trace_params& params);
  void cancel();

  bool running() const { return jobs_.busy(); }
  double progress() const;  // 0..1 of the running still
  std::shared_ptr<const still_result> result() const;

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<trace_progress> progress_;  // of the newest still started; each still has its own
  std::shared_ptr<const still_result> result_;
  std::uint64_t finished_ = 0;
  background_worker jobs_;  // last: destroyed first, so no still outlives the members it writes
};

}  // namespace bounce
