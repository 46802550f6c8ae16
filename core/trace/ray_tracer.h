// Ray-traced stills: a Whitted tracer (Whitted 1980) whose diffuse term can
// come from a radiosity solution (two-pass: Wallace, Cohen & Greenberg
// 1987), and an unbiased path tracer for reference images. GL-free; the
// viewer and `bounce trace` both call trace_image.
#pragma once

#include <atomic>
#include <cstdint>

#include "image/image.h"
#include "radiosity/radiosity_field.h"
#include "trace/ray_scene.h"

namespace bounce {

enum class integrator { whitted, path };

// Where the Whitted tracer's diffuse term comes from.
enum class diffuse_source {
  radiosity,      // all of it from the solution: L = (B - E) / pi, times the texture's detail
  traced_direct,  // direct light by shadow rays (sharp shadows), the rest from the solution
  ambient,        // one pass: direct light by shadow rays plus a constant ambient irradiance
};

struct trace_params {
  integrator method = integrator::whitted;
  int spp = 1;                      // samples per pixel; 1 = the pixel centre, more are stratified
  int adaptive_spp = 0;             // > 0: pixels that differ from a neighbour get this many samples
  double adaptive_contrast = 0.05;  // ... when |a - b| / (a + b) of their luminances exceeds this
  int max_depth = 8;                // Whitted: depth of the specular tree
  int max_path = 1000;              // path: longest path (Russian roulette ends them long before)
  double min_weight = 1e-3;         // Whitted: branches weighted less than this are not traced
  int light_samples = 16;           // Whitted: shadow rays to area emitters per shading point
  diffuse_source diffuse = diffuse_source::traced_direct;
  rgb ambient_irradiance{0.0};  // diffuse_source::ambient
  int roulette_depth = 3;       // path: Russian roulette from this bounce on
  std::uint64_t seed = 1;       // the picture is a function of the seed alone
  bool parallel = true;         // tiles on TBB's threads
};

// Shared with the thread that shows progress; `cancel` stops the tracer
// between rows (the image is then incomplete and stats.cancelled is set).
struct trace_progress {
  std::atomic<long> pixels_done{0};
  std::atomic<long> pixels_total{0};
  std::atomic<bool> cancel{false};
};

struct trace_stats {
  std::uint64_t primary_rays = 0;
  std::uint64_t shadow_rays = 0;
  std::uint64_t secondary_rays = 0;  // reflection, refraction and path bounces
  std::uint64_t refined_pixels = 0;  // adaptive supersampling
  double seconds = 0.0;
  bool cancelled = false;
};

// Traces the scene as `view` sees it, at the view's size (any camera: the
// scene's own is s.view). `rays` is the ray scene of `s`. `field` is the
// radiosity solution for the two-pass modes (required for
// diffuse_source::radiosity/traced_direct with the Whitted integrator;
// ignored by the path tracer).
image trace_image(const scene& s, const camera& view, const ray_scene& rays, const radiosity_field* field,
                  const trace_params& params, trace_progress* progress = nullptr, trace_stats* stats = nullptr);

}  // namespace bounce
