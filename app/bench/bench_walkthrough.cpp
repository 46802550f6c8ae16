#include "bench/bench_walkthrough.h"

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
#include "bench/bench_references.h"
#include "common/exit_code.h"
#include "measure/picture_judge.h"
#include "measure/walkthrough.h"
#include "scene/procedural.h"
#include "trace/ray_scene.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct walk_scene {
  const char* name;
  double solve_seconds;  // the one solve's time limit
};

struct walk_plan {
  std::vector<walk_scene> scenes;
  int views = 50;
  int size = 256;
  int reference_spp = 128;
  int path_max_spp = 64;
};

walk_plan make_walk_plan(const std::string& suite) {
  walk_plan plan;
  if (suite == "walkthrough-quick") {  // a smoke run: three views of a small room
    plan.scenes = {{"box-room-10", 10.0}};
    plan.views = 3;
    plan.size = 64;
    plan.reference_spp = 64;
    plan.path_max_spp = 16;
  } else {
    plan.scenes = {{"box-room-60", 30.0}, {"interior-1m", 60.0}};
  }
  return plan;
}

// The reference of view `index` of the walk, from the cache or traced now.
bool walk_reference(const std::string& out_dir, const scene& s, const ray_scene& rays, const camera& view, int index,
                    const walk_plan& plan, image& out, json& note) {
  const fs::path path = fs::path(out_dir) / "reference" /
                        ("walk-" + s.source + "-" + std::to_string(index) + "of" + std::to_string(plan.views) + "-" +
                         std::to_string(plan.size) + "px-" + std::to_string(plan.reference_spp) + "spp.pfm");
  std::string error;
  if (fs::exists(path)) {
    if (!read_pfm(path.string(), out, error)) {
      std::cerr << "error: " << error << "\n";
      return false;
    }
    note["cached"] = true;
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  out = path_reference(s, view, rays, plan.reference_spp, 1);
  note["cached"] = false;
  note["seconds"] =
      note.value("seconds", 0.0) + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return cache_reference(path, out);
}

std::string percent_to_a_tenth(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f%%", 100.0 * v);
  return b;
}

std::string fixed(double v, int digits) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

}  // namespace

bool is_walkthrough_suite(const std::string& suite) {
  return suite == "walkthrough" || suite == "walkthrough-quick";
}

int run_walkthrough_bench(const bench_options& options) {
  const walk_plan plan = make_walk_plan(options.suite);
  std::error_code ec;
  fs::create_directories(fs::path(options.out_dir) / "reference", ec);
  if (ec) {
    std::cerr << "error: " << options.out_dir << ": " << ec.message() << "\n";
    return exit_input_error;
  }
  std::optional<tbb::global_control> limit;
  if (options.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(options.threads));
  const auto start = std::chrono::steady_clock::now();
  json results = {{"suite", options.suite},
                  {"machine", {{"cpu", cpu_model()}, {"threads", std::thread::hardware_concurrency()}}},
                  {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)},
                  {"views", plan.views},
                  {"picture_size", plan.size},
                  {"reference_spp", plan.reference_spp},
                  {"path_max_spp", plan.path_max_spp},
                  {"scenes", json::array()}};
  std::string md = "# Walkthrough\n\nMachine: " + cpu_model() + ", " +
                   std::to_string(std::thread::hardware_concurrency()) + " threads. " + std::to_string(plan.views) +
                   " views at " + std::to_string(plan.size) + "x" + std::to_string(plan.size) +
                   " along a path through each scene. Radiosity (hierarchical, its defaults, no view) solves once "
                   "and draws every view from the one solution (the Gouraud view's light, ray cast at 4 spp); the "
                   "path tracer renders each view at 1, 2, 4, ... samples per pixel until its error is at most the "
                   "radiosity picture's, or " +
                   std::to_string(plan.path_max_spp) +
                   " spp. Error: relative RMSE after 4x4 block averaging, emitters left out, against a " +
                   std::to_string(plan.reference_spp) + "-spp path-traced reference of each view.\n\n";
  int failures = 0;
  for (const walk_scene& ws : plan.scenes) {
    scene s;
    std::string error;
    if (!make_procedural_scene(ws.name, s, error)) {
      std::cerr << "error: " << error << "\n";
      return exit_input_error;
    }
    s.view.width = s.view.height = plan.size;
    const std::vector<camera> views = procedural_walk(s, plan.views);
    std::vector<image> references(views.size());
    json reference_note = json::object();
    std::printf("bench: walkthrough %s: references (%d views, %d spp) ...", ws.name, plan.views, plan.reference_spp);
    std::fflush(stdout);
    {
      const ray_scene rays(s);  // one BVH for every view's reference
      for (std::size_t i = 0; i < views.size(); ++i)
        if (!walk_reference(options.out_dir, s, rays, views[i], int(i), plan, references[i], reference_note))
          return exit_input_error;
    }
    std::printf(" %.1f s\n", reference_note.value("seconds", 0.0));
    std::printf("bench: walkthrough %s: solving once, then %zu views ...", ws.name, views.size());
    std::fflush(stdout);
    walkthrough_settings settings;
    settings.solver.stop.remaining = 1e-3;
    settings.solver.stop.seconds = ws.solve_seconds;
    settings.path_max_spp = plan.path_max_spp;
    const walkthrough_result r = run_walkthrough(s, views, references, settings);
    if (!r.error.empty()) {
      std::printf(" failed\n");
      std::cerr << "error: " << ws.name << ": " << r.error << "\n";
      ++failures;
      continue;
    }
    double drawn = 0.0, traced = 0.0, radiosity_sum = 0.0, path_sum = 0.0;
    int reached = 0;
    json per_view = json::array();
    for (std::size_t i = 0; i < r.views.size(); ++i) {
      const walkthrough_view& v = r.views[i];
      drawn += v.radiosity_seconds;
      traced += v.path_seconds;
      radiosity_sum += v.radiosity_error;
      path_sum += v.path_error;
      reached += v.path_reached;
      per_view.push_back({{"view", i},
                          {"eye", {views[i].eye.x, views[i].eye.y, views[i].eye.z}},
                          {"target", {views[i].target.x, views[i].target.y, views[i].target.z}},
                          {"radiosity_error", v.radiosity_error},
                          {"radiosity_seconds", v.radiosity_seconds},
                          {"path_error", v.path_error},
                          {"path_spp", v.path_spp},
                          {"path_seconds", v.path_seconds},
                          {"path_reached", v.path_reached}});
    }
    const double n = double(std::max<std::size_t>(1, r.views.size()));
    const double radiosity_total = r.solve_seconds + drawn, path_total = r.path_bvh_seconds + traced;
    std::printf(" radiosity %.1f s (solve %.1f s), path tracer %.1f s\n", radiosity_total, r.solve_seconds, path_total);
    results["scenes"].push_back({{"scene", ws.name},
                                 {"triangles", triangle_count(s)},
                                 {"elements", r.elements},
                                 {"links", r.links},
                                 {"residual", r.residual},
                                 {"converged", r.converged},
                                 {"solve_time_limit", ws.solve_seconds},
                                 {"setup_seconds", r.setup_seconds},
                                 {"solve_seconds", r.solve_seconds},
                                 {"draw_seconds", drawn},
                                 {"radiosity_seconds", radiosity_total},
                                 {"path_bvh_seconds", r.path_bvh_seconds},
                                 {"path_seconds", path_total},
                                 {"path_views_reached", reached},
                                 {"references", reference_note},
                                 {"views", per_view}});
    md += "## " + std::string(ws.name) + "\n\n" + std::to_string(triangle_count(s)) + " triangles; " +
          std::to_string(r.elements) + " elements, " + std::to_string(r.links) + " links, residual " +
          fixed(100.0 * r.residual, 3) + "%" + (r.converged ? "" : " (stopped by its time limit)") + ".\n\n" +
          "| | total time | per view | mean error | views |\n|---|---:|---:|---:|---:|\n" +
          "| radiosity: one solve, every view drawn | " + fixed(radiosity_total, 1) + " s (solve " +
          fixed(r.solve_seconds, 1) + " s) | " + fixed(drawn / n, 2) + " s | " + percent_to_a_tenth(radiosity_sum / n) +
          " | " + std::to_string(r.views.size()) + " |\n" + "| path tracer: each view to the same error | " +
          fixed(path_total, 1) + " s | " + fixed(traced / n, 2) + " s | " + percent_to_a_tenth(path_sum / n) + " | " +
          std::to_string(reached) + " of " + std::to_string(r.views.size()) + " reached it |\n\n" +
          "| view | radiosity error | drawn in | path tracer error | spp | traced in "
          "|\n|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t i = 0; i < r.views.size(); ++i) {
      const walkthrough_view& v = r.views[i];
      md += "| " + std::to_string(i) + " | " + percent_to_a_tenth(v.radiosity_error) + " | " +
            fixed(v.radiosity_seconds, 2) + " s | " + percent_to_a_tenth(v.path_error) +
            (v.path_reached ? "" : " (not reached)") + " | " + std::to_string(v.path_spp) + " | " +
            fixed(v.path_seconds, 2) + " s |\n";
    }
    md += "\n";
  }
  results["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string error;
  if (!write_file((fs::path(options.out_dir) / "walkthrough.json").string(), results.dump(1) + "\n", error) ||
      !write_file((fs::path(options.out_dir) / "walkthrough.md").string(), md, error)) {
    std::cerr << "error: " << error << "\n";
    return exit_input_error;
  }
  std::printf("bench: walkthrough in %.1f s; results in %s (walkthrough.json, walkthrough.md)\n",
              results["seconds"].get<double>(), options.out_dir.c_str());
  return failures ? exit_input_error : exit_ok;
}

}  // namespace bounce
