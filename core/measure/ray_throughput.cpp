#include "measure/ray_throughput.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "base/directions.h"
#include "base/parallel.h"
#include "scene/camera_math.h"

namespace bounce {
namespace {

void add_ray(ray_batch& b, const vec3& origin, const vec3& direction, double t_min) {
  b.origins.push_back(origin);
  b.directions.push_back(direction);
  float_ray r;
  for (int c = 0; c < 3; ++c) {
    r.origin[c] = float(origin[c]);
    r.direction[c] = float(direction[c]);
  }
  r.t_min = float(t_min);
  b.floats.push_back(r);
}

// Casts rays [begin, end) of `batch` with query `q`; returns the hits.
std::size_t cast(const ray_scene& rays, const ray_batch& batch, ray_query q, std::size_t begin, std::size_t end,
                 std::vector<std::optional<ray_hit>>& scratch) {
  std::size_t hits = 0;
  switch (q) {
    case ray_query::bounce_single:
      for (std::size_t k = begin; k < end; ++k)
        hits += rays.intersect(batch.origins[k], batch.directions[k], batch.t_min).has_value();
      return hits;
    case ray_query::bounce_packets: {
      scratch.resize(end - begin);
      rays.intersect_packets(std::span(batch.origins).subspan(begin, end - begin),
                             std::span(batch.directions).subspan(begin, end - begin), scratch, batch.t_min);
      for (const auto& h : scratch) hits += h.has_value();
      return hits;
    }
    case ray_query::embree_single:
      return rays.embree_closest_hits(std::span(batch.floats).subspan(begin, end - begin), 1);
    case ray_query::embree_packet4:
      return rays.embree_closest_hits(std::span(batch.floats).subspan(begin, end - begin), 4);
    case ray_query::embree_packet8:
      return rays.embree_closest_hits(std::span(batch.floats).subspan(begin, end - begin), 8);
    case ray_query::embree_packet16:
      return rays.embree_closest_hits(std::span(batch.floats).subspan(begin, end - begin), 16);
  }
  return hits;
}

}  // namespace

ray_batch primary_rays(const camera& view) {
  ray_batch b;
  constexpr int tile = 4;
  for (int ty = 0; ty < view.height; ty += tile)
    for (int tx = 0; tx < view.width; tx += tile)
      for (int y = ty; y < std::min(ty + tile, view.height); ++y)
        for (int x = tx; x < std::min(tx + tile, view.width); ++x)
          add_ray(b, view.eye, camera_ray_direction(view, x + 0.5, y + 0.5), 0.0);
  return b;
}

ray_batch bounce_rays(const ray_scene& rays, const ray_batch& primary, std::uint64_t seed) {
  ray_batch b;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t k = 0; k < primary.origins.size(); ++k) {
    const vec3& d = primary.directions[k];
    const auto hit = rays.intersect(primary.origins[k], d, primary.t_min);
    if (!hit) continue;
    // The side the ray arrived from, as the tracers shade it.
    const bool front = glm::dot(d, hit->face_normal) < 0.0;
    const vec3 n_face = front ? hit->face_normal : -hit->face_normal;
    const vec3 n = front ? hit->normal : -hit->normal;
    const double u1 = uniform(rng), u2 = uniform(rng);
    vec3 dir = cosine_direction(n, u1, u2);
    if (glm::dot(dir, n_face) <= 0.0) dir = glm::reflect(dir, n_face);  // below the true surface: mirrored back up
    add_ray(b, hit->point + rays.surface_offset() * n_face, dir, 0.0);
  }
  return b;
}

const char* name_of(ray_query q) {
  switch (q) {
    case ray_query::bounce_single:
      return "Bounce intersect";
    case ray_query::bounce_packets:
      return "Bounce intersect_packets (8)";
    case ray_query::embree_single:
      return "Embree rtcIntersect1";
    case ray_query::embree_packet4:
      return "Embree rtcIntersect4";
    case ray_query::embree_packet8:
      return "Embree rtcIntersect8";
    case ray_query::embree_packet16:
      return "Embree rtcIntersect16";
  }
  return "";
}

bool is_bounce(ray_query q) {
  return q == ray_query::bounce_single || q == ray_query::bounce_packets;
}

std::vector<ray_rate> measure_ray_rates(const ray_scene& rays, const ray_batch& batch,
                                        const std::vector<ray_query>& queries, int passes) {
  constexpr std::size_t block = 256;  // a multiple of every packet width
  const std::size_t count = batch.origins.size(), blocks = (count + block - 1) / block;
  std::vector<std::vector<double>> seconds(queries.size());
  std::vector<ray_rate> out(queries.size());
  for (int pass = 0; pass < std::max(passes, 1); ++pass)
    for (std::size_t i = 0; i < queries.size(); ++i) {
      std::atomic<std::size_t> hits{0};
      const auto start = std::chrono::steady_clock::now();
      for_each_block(true, blocks, 1, [&](std::size_t first, std::size_t last) {
        std::vector<std::optional<ray_hit>> scratch;
        std::size_t local = 0;
        for (std::size_t b = first; b < last; ++b)
          local += cast(rays, batch, queries[i], b * block, std::min(count, (b + 1) * block), scratch);
        hits += local;
      });
      seconds[i].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      out[i].hits = hits;
    }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    std::vector<double>& s = seconds[i];
    std::sort(s.begin(), s.end());
    ray_rate& r = out[i];
    r.query = queries[i];
    r.rays = count;
    r.best_seconds = s.front();
    r.median_seconds = s[s.size() / 2];
    r.rays_per_second = r.best_seconds > 0 ? double(count) / r.best_seconds : 0.0;
  }
  return out;
}

}  // namespace bounce
