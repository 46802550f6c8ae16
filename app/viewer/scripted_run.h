// The choreography of a scripted window run (`bounce view --frames N`, the
// window tests and screenshots): a still traced halfway and waited for, the
// error plot's reference and first measurement waited for, then a
// screenshot, a report of what was shown and how fast, and the exit.
#pragma once

#include <cstddef>
#include <string>

#include "viewer/error_tracker.h"
#include "viewer/still_job.h"

namespace bounce {

struct viewer_options;

// Frame and upload times of the window, reported after a scripted run.
struct frame_timing {
  double frame_ms_sum = 0.0, frame_ms_max = 0.0, upload_ms_sum = 0.0, upload_ms_max = 0.0;
  int frames = 0, uploads = 0;
  double mesh_upload_ms_max = 0.0;  // a new mesh (scene, density, refinement pass)
  int mesh_uploads = 0;
  // From the window's start (the scene is built or read before): the first
  // frame with the mesh, and the first with light carried by the solver.
  double first_mesh_ms = -1.0, first_lit_ms = -1.0;
  void frame(int index, double ms);  // start-up frames (mesh upload, font atlas) are left out
  void upload(double ms);
  void mesh_upload(double ms);
};

class scripted_run {
 public:
  explicit scripted_run(const viewer_options& options);

  bool active() const;
  // Whether to start the scripted still at `frame` (halfway through).
  bool wants_still(int frame, bool has_mesh) const;
  // Saves the first finished still to the --still path; false if that fails.
  bool take_still(const still_result& still, double exposure, int frame);
  // The last frame: every frame drawn, the still saved and shown, the
  // error plot measured.
  // With --refined-passes, also the refinement at rest showing that many
  // passes (`shown_passes`), waited for up to ten times the frames asked.
  bool at_end(int frame, const error_status& errors, int shown_passes) const;
  // After the last frame: what the error plot shows and how fast the window was.
  void report(const error_status& errors, const frame_timing& timing, int width, int height, std::size_t triangles,
              std::size_t meshed_triangles) const;

 private:
  const viewer_options& options_;
  int still_saved_frame_ = -1;  // the frame the still was written in
};

}  // namespace bounce
