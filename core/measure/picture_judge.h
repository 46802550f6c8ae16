// Pictures against a reference picture: the error of a solution through
// the picture it makes (the Gouraud view's diffuse term, or a two-pass
// still), box-filtered, with the emitters' pixels left out, and its mean
// per material (surface_means.h). The bench and the window's error plot
// both use it.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "image/image.h"
#include "measure/curves.h"
#include "measure/exact_solutions.h"
#include "measure/surface_means.h"
#include "mesh/patch_mesh.h"
#include "trace/ray_scene.h"
#include "trace/ray_tracer.h"

namespace bounce {

// What errors are measured against. For exact_kind::none, `picture` is the
// path-traced reference of s.view (linear radiance) and the comparison is
// made after box-filtering `downsample` x `downsample` blocks, with the
// pixels that see an emitter (and their neighbours) left out: their edges'
// aliasing would otherwise decide the figure.
struct bench_truth {
  exact_kind exact = exact_kind::none;
  image picture;
  int downsample = 4;
  double exclude_above = 0.0;  // radiance above which a reference pixel counts as an emitter
  int still_spp = 4;           // samples per pixel of the pictures of a solution
};

// Measures solutions of a scene through pictures of them against the
// truth's reference picture: both box-filtered, the emitters' pixels left
// out of both. The bench and the viewer's error plot both use it. The scene
// must outlive the judge.
class picture_judge {
 public:
  // Judges pictures of `s` as `view` sees them (the reference's camera and
  // size), tracing with `rays` (s's, shared by judges of many views) or
  // with its own.
  picture_judge(const scene& s, const camera& view, const bench_truth& truth,
                std::shared_ptr<const ray_scene> rays = nullptr);

  struct verdict {
    double error = not_measured, max_error = not_measured;
    double seconds = 0.0, cpu_seconds = 0.0;  // to make the picture (radiosity field + tracing)
    std::vector<surface_mean> surfaces;       // the picture's mean per material, against the reference's
  };
  verdict judge(const image& picture) const;
  // A still of the solution at the reference's size: all diffuse light from
  // it (diffuse_source::radiosity, what the Gouraud view shows) or direct
  // light by shadow rays and the rest from it (traced_direct: two-pass).
  verdict judge_solution(const patch_mesh& mesh, std::span<const rgb> radiosity, std::span<const rgb> direct,
                         diffuse_source source) const;
  const ray_scene& rays() const { return *rays_; }

 private:
  const scene& scene_;
  camera view_;
  int downsample_ = 4, still_spp_ = 4;
  std::shared_ptr<const ray_scene> rays_;
  image reference_;       // box-filtered
  image full_reference_;  // at full size, for the means per material
  std::vector<int> material_;
};

// Radiance above which a reference pixel counts as showing an emitter: half
// the dimmest emitting material's brightest channel (infinity: no emitters).
double emitter_threshold(const scene& s);

// The path-traced reference picture of s.view: `spp` samples per pixel.
image path_reference(const scene& s, int spp, std::uint64_t seed);
// The same of `view`, with s's ray scene already built (many views of one scene).
image path_reference(const scene& s, const camera& view, const ray_scene& rays, int spp, std::uint64_t seed);

}  // namespace bounce
