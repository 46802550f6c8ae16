#include "viewer/scripted_run.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "image/image.h"
#include "viewer/viewer.h"

namespace bounce {

void frame_timing::frame(int index, double ms) {
  if (index <= 10) return;  // past start-up
  frame_ms_sum += ms;
  frame_ms_max = std::max(frame_ms_max, ms);
  ++frames;
}

void frame_timing::mesh_upload(double ms) {
  mesh_upload_ms_max = std::max(mesh_upload_ms_max, ms);
  ++mesh_uploads;
}

void frame_timing::upload(double ms) {
  upload_ms_sum += ms;
  upload_ms_max = std::max(upload_ms_max, ms);  // a refined mesh's upload, with adaptive meshing
  ++uploads;
}

scripted_run::scripted_run(const viewer_options& options) : options_(options) {}

bool scripted_run::active() const {
  return options_.frames > 0;
}

bool scripted_run::wants_still(int frame, bool has_mesh) const {
  return !options_.still_path.empty() && has_mesh && still_saved_frame_ < 0 &&
         frame == std::max(1, options_.frames / 2);
}

bool scripted_run::take_still(const still_result& still, double exposure, int frame) {
  if (options_.still_path.empty() || still_saved_frame_ >= 0) return true;
  still_saved_frame_ = frame;
  std::string error;
  const std::vector<unsigned char> rows = to_srgb_rows(still.picture, exposure);
  if (!write_png(options_.still_path, still.picture.width, still.picture.height, 3, rows.data(), error)) {
    std::printf("%s\n", error.c_str());
    return false;
  }
  std::printf("still: %s, wrote %s\n", still.summary.c_str(), options_.still_path.c_str());
  return true;
}

bool scripted_run::at_end(int frame, const error_status& errors, int shown_passes) const {
  if (!active() || frame < options_.frames) return false;
  // The still's window needs a frame or two to be laid out after it arrives.
  const bool still_pending = !options_.still_path.empty() && (still_saved_frame_ < 0 || frame < still_saved_frame_ + 3);
  const bool error_pending = options_.error_plot && (!errors.ready || errors.history.empty());
  const bool refine_pending = shown_passes < options_.refined_passes && frame < 10 * options_.frames;
  return !still_pending && !error_pending && !refine_pending;
}

void scripted_run::report(const error_status& errors, const frame_timing& timing, int width, int height,
                          std::size_t triangles, std::size_t meshed_triangles) const {
  if (options_.error_plot) {
    if (errors.history.empty())
      std::printf("error plot: no measurement yet (%s)\n", errors.summary.c_str());
    else
      std::printf("error plot: %zu measurements; error %.4f at %.3f s, %.4f at %.3f s (%s)\n", errors.history.size(),
                  errors.history.front().error, errors.history.front().seconds, errors.history.back().error,
                  errors.history.back().seconds, errors.summary.c_str());
  }
  if (timing.frames > 0)
    std::printf(
        "view: %dx%d, %zu triangles (%zu as meshed), %d frames: %.2f ms per frame (%.1f fps), worst %.1f ms; "
        "radiosity upload %.3f ms (mean of %d, largest %.2f ms); mesh upload %.1f ms (largest of %d)\n",
        width, height, triangles, meshed_triangles, timing.frames, timing.frame_ms_sum / timing.frames,
        1000.0 * timing.frames / timing.frame_ms_sum, timing.frame_ms_max,
        timing.uploads ? timing.upload_ms_sum / timing.uploads : 0.0, timing.uploads, timing.upload_ms_max,
        timing.mesh_upload_ms_max, timing.mesh_uploads);
  auto when = [](double ms) { return ms < 0.0 ? std::string("none") : std::to_string(int(ms + 0.5)) + " ms"; };
  std::printf("view: after the window opened, first picture of the mesh %s, first lit picture %s\n",
              when(timing.first_mesh_ms).c_str(), when(timing.first_lit_ms).c_str());
}

}  // namespace bounce
