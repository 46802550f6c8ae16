// Refinement at rest, as in Blender's viewport: when the camera has been
// still for a moment, passes of the still's integrator (two-pass Whitted
// from the latest radiosity solution, a few jittered samples per pixel a
// pass) accumulate in the background, and the window shows them blended
// with the live Gouraud view by their noise (image/pass_blend.h): the live
// picture where it agrees with the passes within their noise, the passes
// where it does not. Moving the camera drops them at once. GL-free: the
// window uploads the picture itself. Nothing here blocks the caller.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>

#include "base/background_worker.h"
#include "image/image.h"
#include "mesh/patch_mesh.h"
#include "radiosity/solution.h"
#include "trace/ray_tracer.h"

namespace bounce {

struct refined_picture {
  image shown;  // linear radiance: `passes` passes blended with the live view
  int passes = 0;
  std::uint64_t run = 0;  // which start() it belongs to
};

class rest_refiner {
 public:
  rest_refiner() = default;
  ~rest_refiner();  // cancels and joins
  rest_refiner(const rest_refiner&) = delete;
  rest_refiner& operator=(const rest_refiner&) = delete;

  // Starts accumulating passes of `view` (at its size) with the solution of
  // `mesh`; a run already going is dropped. At most `max_passes` passes.
  // `live`: the live view's radiance at the view's size, or empty (then the
  // passes' mean is shown).
  void start(std::shared_ptr<const scene> source, const camera& view, std::shared_ptr<const patch_mesh> mesh,
             std::shared_ptr<const radiosity_snapshot> solution, image live, int samples_per_pass = 2,
             int max_passes = 64);
  // Drops the run: its passes are forgotten, the one being traced stops soon.
  void stop();

  bool active() const { return run_ != 0; }
  // The mean of the current run's passes so far, or null before the first.
  std::shared_ptr<const refined_picture> picture() const;

 private:
  void trace_passes(std::uint64_t run, const scene& source, const camera& view, const patch_mesh* mesh,
                    const radiosity_snapshot* solution, const image& live, int samples_per_pass, int max_passes);

  mutable std::mutex mutex_;
  std::shared_ptr<const refined_picture> picture_;
  std::shared_ptr<trace_progress> progress_;  // of the pass being traced, to cancel it
  std::atomic<std::uint64_t> latest_{0};      // the newest run started; older runs stop
  std::uint64_t run_ = 0;                     // the caller's view of the current run (0: none)
  background_worker jobs_;                    // last: destroyed first
};

}  // namespace bounce
