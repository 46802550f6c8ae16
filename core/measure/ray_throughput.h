// The ray core's speed against Embree's own on the same rays (issue #16,
// docs/performance.md "Ray core"): a camera's primary rays (coherent) and
// diffuse bounce rays from where they land (incoherent), cast through
// ray_scene::intersect one at a time (what the tracers do), through
// ray_scene::intersect_packets, and through Embree directly, one
// rtcIntersect1 call per ray or packets of rtcIntersect4/8/16. GL-free;
// `bounce bench --suite rays` reports it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace bounce {

// One set of rays, in double (for ray_scene) and in floats (for Embree
// directly), in the order every query casts them.
struct ray_batch {
  std::vector<vec3> origins, directions;
  double t_min = 0.0;
  std::vector<float_ray> floats;  // the same rays as Embree stores them
};

// The primary rays through the pixel centres of `view` at its size, in
// tiles of 4 x 4 pixels (row by row inside a tile, tiles row by row), so
// that a packet of 4, 8 or 16 consecutive rays is a 4 x 1, 4 x 2 or 4 x 4
// block of pixels.
ray_batch primary_rays(const camera& view);

// Diffuse bounce rays: from each hit of `primary` (the side the primary
// ray arrived from, lifted off by surface_offset()), one cosine-distributed
// direction about the shading normal, from a random stream of `seed`.
// Rays that hit nothing give none.
ray_batch bounce_rays(const ray_scene& rays, const ray_batch& primary, std::uint64_t seed);

enum class ray_query {
  bounce_single,   // ray_scene::intersect, one call per ray
  bounce_packets,  // ray_scene::intersect_packets, packets of 8
  embree_single,   // rtcIntersect1, one call per ray
  embree_packet4,  // rtcIntersect4
  embree_packet8,  // rtcIntersect8
  embree_packet16  // rtcIntersect16
};
const char* name_of(ray_query q);
bool is_bounce(ray_query q);

struct ray_rate {
  ray_query query = ray_query::bounce_single;
  std::size_t rays = 0;
  std::size_t hits = 0;          // the same for every query on the same rays, or one of them is wrong
  double best_seconds = 0.0;     // the fastest pass
  double median_seconds = 0.0;   // the middle pass
  double rays_per_second = 0.0;  // from the fastest pass
};

// Casts `batch` with each of `queries`, `passes` times, interleaved (pass
// 1 of every query, then pass 2, ...) so that a burst of load from
// elsewhere on the machine hits them alike; on TBB's threads in blocks of
// 256 rays (within the caller's tbb::global_control limit).
std::vector<ray_rate> measure_ray_rates(const ray_scene& rays, const ray_batch& batch,
                                        const std::vector<ray_query>& queries, int passes);

}  // namespace bounce
