#include "bench/bench_rays.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <thread>

#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include "base/whole_file.h"
#include "common/exit_code.h"
#include "measure/ray_throughput.h"
#include "scene/procedural.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ray_bench_scene {
  const char* name;
  const char* path;
};

const ray_bench_scene ray_scenes[] = {
    {"whitted", "embedded:whitted/whitted.json"},
    {"cornell", default_scene_path},
    {"interior-100k", "generated:interior-100k"},
};

constexpr int picture_size = 512;
constexpr int passes = 7;  // the fastest of 7 interleaved passes counts
constexpr std::uint64_t bounce_seed = 1;

const std::vector<ray_query> coherent_queries = {
    ray_query::bounce_single,  ray_query::bounce_packets, ray_query::embree_single,
    ray_query::embree_packet4, ray_query::embree_packet8, ray_query::embree_packet16,
};
const std::vector<ray_query> incoherent_queries = {
    ray_query::bounce_single,
    ray_query::bounce_packets,
    ray_query::embree_single,
    ray_query::embree_packet8,
};

const ray_rate* find_rate(const std::vector<ray_rate>& rates, ray_query q) {
  for (const ray_rate& r : rates)
    if (r.query == q) return &r;
  return nullptr;
}

// "12.3" Mrays/s, or "-" for a query not run on that set.
std::string mrays(const ray_rate* r) {
  if (!r) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", r->rays_per_second * 1e-6);
  return buffer;
}

std::string ratio(double a, double b) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.0f%%", b > 0 ? 100.0 * a / b : 0.0);
  return buffer;
}

}  // namespace

int run_ray_bench(const bench_options& options) {
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) {
    std::cerr << "error: " << options.out_dir << ": " << ec.message() << "\n";
    return exit_input_error;
  }
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(options.threads));
  const auto threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);

  json results = {
      {"suite", "rays"},
      {"machine", {{"cpu", cpu_model()}, {"threads", std::thread::hardware_concurrency()}}},
      {"threads", threads},
      {"picture_size", picture_size},
      {"passes", passes},
      {"native_packets",
       {{"4", ray_scene::native_packet(4)}, {"8", ray_scene::native_packet(8)}, {"16", ray_scene::native_packet(16)}}},
      {"scenes", json::array()}};
  std::string md =
      "| scene | triangles | rays | count | Bounce intersect | Bounce packets of 8 | rtcIntersect1 | "
      "rtcIntersect4 | rtcIntersect8 | rtcIntersect16 | Bounce / rtcIntersect1 | Bounce / fastest "
      "Embree |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  int disagreements = 0;
  for (const ray_bench_scene& rs : ray_scenes) {
    scene s;
    load_report report;
    if (!load_scene(rs.path, s, report)) {
      std::cerr << "error: " << report.error << "\n";
      return exit_input_error;
    }
    s.view.width = s.view.height = picture_size;
    std::printf("bench: %-14s building the ray scene ...", rs.name);
    std::fflush(stdout);
    const auto build_start = std::chrono::steady_clock::now();
    const ray_scene rays(s);
    const double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
    std::printf(" %.2f s\n", build_seconds);
    const ray_batch primary = primary_rays(s.view);
    const ray_batch incoherent = bounce_rays(rays, primary, bounce_seed);
    json scene_json = {{"scene", rs.name},
                       {"path", rs.path},
                       {"triangles", triangle_count(s)},
                       {"build_seconds", build_seconds},
                       {"sets", json::array()}};
    const std::pair<const char*, const ray_batch*> sets[] = {{"primary (coherent)", &primary},
                                                             {"diffuse bounce (incoherent)", &incoherent}};
    for (const auto& [set_name, batch] : sets) {
      const bool coherent = batch == &primary;
      std::printf("bench: %-14s %-28s %zu rays ...", rs.name, set_name, batch->origins.size());
      std::fflush(stdout);
      const std::vector<ray_rate> rates =
          measure_ray_rates(rays, *batch, coherent ? coherent_queries : incoherent_queries, passes);
      // Every query casts the same rays, so they must agree on how many hit.
      json queries = json::array();
      double fastest_embree = 0.0;
      for (const ray_rate& r : rates) {
        if (!is_bounce(r.query)) fastest_embree = std::max(fastest_embree, r.rays_per_second);
        queries.push_back({{"query", name_of(r.query)},
                           {"rays", r.rays},
                           {"hits", r.hits},
                           {"best_seconds", r.best_seconds},
                           {"median_seconds", r.median_seconds},
                           {"rays_per_second", r.rays_per_second}});
        if (r.hits != rates.front().hits) {
          std::fprintf(stderr, "\nerror: %s, %s: %s hits %zu rays, %s %zu\n", rs.name, set_name, name_of(r.query),
                       r.hits, name_of(rates.front().query), rates.front().hits);
          ++disagreements;
        }
      }
      const ray_rate* bounce = find_rate(rates, ray_query::bounce_single);
      const ray_rate* embree = find_rate(rates, ray_query::embree_single);
      std::printf(" Bounce %.2f Mrays/s, rtcIntersect1 %.2f, fastest Embree %.2f\n", bounce->rays_per_second * 1e-6,
                  embree->rays_per_second * 1e-6, fastest_embree * 1e-6);
      scene_json["sets"].push_back({{"set", set_name},
                                    {"rays", batch->origins.size()},
                                    {"hits", rates.front().hits},
                                    {"bounce_over_embree_single", bounce->rays_per_second / embree->rays_per_second},
                                    {"bounce_over_fastest_embree", bounce->rays_per_second / fastest_embree},
                                    {"queries", queries}});
      char row[512];
      std::snprintf(row, sizeof row, "| %s | %zu | %s | %zu | %s | %s | %s | %s | %s | %s | %s | %s |\n", rs.name,
                    triangle_count(s), set_name, batch->origins.size(), mrays(bounce).c_str(),
                    mrays(find_rate(rates, ray_query::bounce_packets)).c_str(), mrays(embree).c_str(),
                    mrays(find_rate(rates, ray_query::embree_packet4)).c_str(),
                    mrays(find_rate(rates, ray_query::embree_packet8)).c_str(),
                    mrays(find_rate(rates, ray_query::embree_packet16)).c_str(),
                    ratio(bounce->rays_per_second, embree->rays_per_second).c_str(),
                    ratio(bounce->rays_per_second, fastest_embree).c_str());
      md += row;
    }
    results["scenes"].push_back(scene_json);
  }
  char notes[512];
  std::snprintf(notes, sizeof notes,
                "\nMrays/s, the fastest of %d interleaved passes over the same rays, on %d thread(s) of %s. "
                "Primary rays through the pixel centres at %d x %d, in 4 x 4 pixel tiles; one cosine-distributed "
                "bounce ray from each primary hit. Embree packets run natively: 4 %s, 8 %s, 16 %s.\n",
                passes, int(threads), cpu_model().c_str(), picture_size, picture_size,
                ray_scene::native_packet(4) ? "yes" : "no", ray_scene::native_packet(8) ? "yes" : "no",
                ray_scene::native_packet(16) ? "yes" : "no");
  md += notes;
  const fs::path json_path = fs::path(options.out_dir) / "rays.json", md_path = fs::path(options.out_dir) / "rays.md";
  std::string error;
  if (!write_file(json_path.string(), results.dump(1) + "\n", error) || !write_file(md_path.string(), md, error)) {
    std::cerr << "error: " << error << "\n";
    return exit_input_error;
  }
  std::cout << "\n" << md << "\nbench: results in " << options.out_dir << " (rays.json, rays.md)\n";
  if (disagreements) {
    std::fprintf(stderr, "error: %d query(ies) disagree on the hits of the same rays\n", disagreements);
    return exit_input_error;
  }
  return exit_ok;
}

}  // namespace bounce
