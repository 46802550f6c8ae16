// Ray-traced stills: a Whitted tracer (Whitted 1980) whose diffuse term can
// come from a radiosity solution (two-pass: Wallace, Cohen & Greenberg
// 1987); the two-pass still with a final gather over that solution and
// caustics from a photon map (Jensen 1996), plain or progressive (Knaus &
// Zwicker 2011); and an unbiased path tracer for reference images.
// GL-free; the viewer and `bounce trace` both call trace_image.
// docs/ray-tracing.md says what each integrator computes.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "image/image.h"
#include "trace/radiosity_field.h"
#include "trace/photon_tracing.h"
#include "trace/ray_scene.h"

namespace bounce {

// whitted: L D S* E, D from the solution or shadow rays (diffuse_source).
// twopass: direct light by shadow rays, caustics (L S+ D) from a photon
//          map, the rest of the diffuse light by a final gather over the
//          radiosity solution, cached (Ward 1988); then S* E.
// ppm:     twopass with the caustics from progressive photon passes.
// path:    everything, unbiased.
enum class integrator { whitted, twopass, ppm, path };

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

  // twopass and ppm (direct light as diffuse_source::traced_direct).
  int gather_rays = 256;         // final gather: stratified cosine rays per irradiance record
  double cache_accuracy = 0.25;  // irradiance cache: Ward's a (smaller: more records); 0: gather at every point
  long photons = -1;             // caustic photons (ppm: per pass); -1: default_caustic_photons; 0: no caustics
  int caustic_k = 80;            // twopass: photons in the density estimate (k nearest)
  double caustic_radius = 0.0;   // twopass: its largest radius; ppm: the first pass's; 0: default_caustic_radius
  int passes = 32;               // ppm: photon passes
  double ppm_alpha = 2.0 / 3.0;  // ppm: r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1)
  std::uint64_t seed = 1;        // the picture is a function of the seed alone
  bool parallel = true;          // tiles on TBB's threads
};

// Shared with the thread that shows progress; `cancel` stops the tracer
// between rows (the image is then incomplete and stats.cancelled is set).
// The twopass and ppm stills go through stages before and after the
// pixels: `stage` says which one the counters describe.
enum class trace_stage { photons, cache, pixels, passes };

struct trace_progress {
  std::atomic<long> pixels_done{0};
  std::atomic<long> pixels_total{0};
  std::atomic<bool> cancel{false};
  std::atomic<trace_stage> stage{trace_stage::pixels};
  photon_progress photons;                 // the photon pass under way (the first one for ppm)
  std::atomic<long> cache_points_done{0};  // pixel-centre shading points checked for a cache record
  std::atomic<long> cache_points_total{0};
  std::atomic<int> passes_done{0};  // ppm
  std::atomic<int> passes_total{0};
  // ppm: called on the tracing thread after each photon pass with the
  // picture so far (the passes' mean caustic), so that a window can show
  // the caustic sharpening. Set before trace_image starts.
  std::function<void(const image& picture, int passes)> pass_done;
};

struct trace_stats {
  std::uint64_t primary_rays = 0;
  std::uint64_t shadow_rays = 0;
  std::uint64_t secondary_rays = 0;  // reflection, refraction and path bounces
  std::uint64_t refined_pixels = 0;  // adaptive supersampling
  // twopass and ppm
  std::uint64_t gather_rays = 0;      // final gather rays (and their specular continuations)
  std::uint64_t cache_records = 0;    // irradiance records made
  std::uint64_t cache_misses = 0;     // shading points no record covered, gathered on the spot
  double cache_seconds = 0.0;         // making the records (included in seconds)
  std::uint64_t photons_emitted = 0;  // all passes
  std::uint64_t photons_stored = 0;
  double photon_seconds = 0.0;  // shooting and density estimation in passes (included in seconds)
  int passes = 0;               // ppm: photon passes done
  double final_radius = 0.0;    // ppm: the last pass's radius
  double seconds = 0.0;
  bool cancelled = false;
};

// Traces the scene as `view` sees it, at the view's size (any camera: the
// scene's own is s.view). `rays` is the ray scene of `s`. `field` is the
// radiosity solution for the two-pass modes (required for
// diffuse_source::radiosity/traced_direct with the Whitted integrator, and
// for twopass and ppm, which throw std::invalid_argument without it;
// ignored by the path tracer). twopass and ppm shoot their own caustic
// photons (progress->photons shows them).
image trace_image(const scene& s, const camera& view, const ray_scene& rays, const radiosity_field* field,
                  const trace_params& params, trace_progress* progress = nullptr, trace_stats* stats = nullptr);

// Caustic photons when trace_params::photons is -1: none if no material
// reflects or transmits specularly (there can be no caustic), else 500 000
// (twopass) or 200 000 per pass (ppm).
long default_caustic_photons(const scene& s, integrator method);

// The caustic radius when trace_params::caustic_radius is 0, as a fraction
// of the scene's bounding-box diagonal: twopass's largest radius (the k
// nearest shrink it) 1/50, ppm's first radius 1/100.
double default_caustic_radius(const scene& s, integrator method);

}  // namespace bounce
