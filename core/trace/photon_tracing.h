// The light pass of photon mapping (Jensen 1996) for caustics: photons
// leave the emitters, follow mirror reflection and refraction only, and are
// stored where they land on a diffuse surface after at least one specular
// event: the paths L S+ D in Heckbert's notation, which shadow rays and a
// radiosity solution cannot find. GL-free; docs/photon-mapping.md.
#pragma once

#include <atomic>
#include <cstdint>

#include "trace/photon_map.h"
#include "trace/ray_scene.h"

namespace bounce {

struct photon_params {
  // Photons emitted, shared among the emitters in proportion to their power
  // (every emitter gets at least one).
  long photon_count = 200000;
  int max_bounces = 16;    // specular events a photon may go through
  std::uint64_t seed = 1;  // the map is a function of the seed alone, on any number of threads
  bool parallel = true;    // blocks of photons on TBB's threads
};

// Shared with a thread that shows progress; `cancel` stops the pass between
// blocks of photons (the map then holds what was traced so far).
struct photon_progress {
  std::atomic<long> photons_done{0};
  std::atomic<long> photons_total{0};
  std::atomic<bool> cancel{false};
};

// Where the emitted power went. Every photon ends exactly once, so
//   emitted + reweighted + passed_on = stored + direct + absorbed + escaped + truncated
// to round-off (photon_power_imbalance).
struct photon_stats {
  std::uint64_t emitted = 0;  // photons
  std::uint64_t stored = 0;   // photons in the map
  int skipped_emitters = 0;   // emitting surfaces that send no photons (quadrics: ray_scene cannot sample them)
  rgb emitted_power{0.0};     // W: the emitters' power, sampled (exact for emitters of one colour)
  rgb stored_power{0.0};      // the map's total
  rgb direct_power{0.0};      // ended on a diffuse surface before any specular event (shadow rays find it)
  rgb absorbed_power{0.0};    // ended on a surface with no diffuse reflectance on that side
  rgb escaped_power{0.0};     // left the scene (to the sky or the background)
  rgb truncated_power{0.0};   // still going after max_bounces specular events
  rgb passed_on_power{0.0};   // stored on a surface that also reflects or transmits specularly, and followed on
  rgb reweighted_power{0.0};  // gained or lost by Russian roulette on coloured weights (zero for grey ones)
  double seconds = 0.0;
  bool cancelled = false;
};

struct caustic_result {
  photon_map map;
  photon_stats stats;
};

// The caustic photon map of the scene. `rays` is the ray scene of `s`.
// Photons leave area emitters (uniformly by area, cosine-weighted about the
// emitting normal: power pi * ke * area in all) and punctual lights
// (scene/lights.h: a point light over the sphere, power 4 pi I; a spot
// within its cone; a sun from a disc over the scene's bounding ball, power
// E pi r^2). Not sources: the sky, and emitting
// quadrics (counted in stats.skipped_emitters).
caustic_result caustic_photons(const scene& s, const ray_scene& rays, const photon_params& params,
                               photon_progress* progress = nullptr);

// What the stats fail to account for: the left side of the balance above
// minus the right, per channel (zero up to round-off).
rgb photon_power_imbalance(const photon_stats& stats);

// Fraction of the emitted power that the map stores (mean over channels).
double caustic_power_fraction(const photon_stats& stats);

}  // namespace bounce
