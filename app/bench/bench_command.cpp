#include "bench/bench_command.h"

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <thread>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "base/whole_file.h"
#include "bench/bench_rays.h"
#include "bench/bench_references.h"
#include "bench/bench_report.h"
#include "bench/bench_suites.h"
#include "bench/bench_walkthrough.h"
#include "common/exit_code.h"
#include "measure/bench.h"
#include "scene/procedural.h"
#include "scene/scene_io.h"

extern char** environ;

namespace bounce {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json point_json(const bench_point& p) {
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json surfaces = json::array();
  for (const surface_mean& m : p.surfaces)
    surfaces.push_back({{"material", m.material}, {"pixels", m.pixels}, {"ratio", number(m.ratio)}});
  return {{"seconds", p.seconds},
          {"cpu_seconds", number(p.cpu_seconds)},
          {"steps", p.steps},
          {"rays", p.rays},
          {"remaining", number(p.remaining)},
          {"error", number(p.error)},
          {"max_error", number(p.max_error)},
          {"power_error", number(p.power_error)},
          {"balance_error", number(p.balance_error)},
          {"residual", number(p.residual)},
          {"elements", p.elements},
          {"surfaces", surfaces}};
}

// A memory figure of this process from /proc/self/status, in MiB (0 if
// unknown): "VmRSS" resident now, "VmHWM" its peak. Read by the child
// itself: the rusage a parent gets from wait4 starts from the parent's
// own peak at the spawn, not from zero.
double status_mib(const std::string& key) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ":", 0) == 0) return std::stod(line.substr(key.size() + 1)) / 1024.0;  // "VmRSS:  1234 kB"
  return 0.0;
}

// Runs case `index` in this process and writes its JSON.
int run_one_case(const suite_plan& plan, int index, const bench_options& options) {
  const std::string& out_dir = options.out_dir;
  const double start_mib = status_mib("VmRSS");  // the program itself, before the run: subtracted from its peak
  const bench_case& c = plan.cases[std::size_t(index)];
  // The thread limit holds for everything the run does with TBB (the
  // solvers, the ray tracer, Embree's BVH builds), measuring included.
  const int thread_limit = c.threads > 0 ? c.threads : options.threads;
  std::optional<tbb::global_control> limit;
  if (thread_limit > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(thread_limit));
  const auto threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  scene s;
  std::string error;
  if (!load_bench_scene(c, plan.picture_size, s, error)) {
    std::cerr << "error: " << error << "\n";
    return exit_input_error;
  }
  bench_setting setting;
  setting.kind = c.kind;
  setting.solver = c.settings;
  setting.measure_error = !c.growth;

  bench_truth truth;
  truth.exact = find_scene(c.scene).exact;
  if (truth.exact == exact_kind::none && setting.measure_error) {
    const fs::path path = reference_path(out_dir, c.scene, plan.picture_size, plan.reference_spp);
    if (!read_pfm(path.string(), truth.picture, error)) {
      std::cerr << "error: " << error << "\n";
      return exit_input_error;
    }
    truth.exclude_above = emitter_threshold(s);
  }
  // A run that does not fit in memory, or throws, is the case's error in
  // its JSON: the suite goes on with its other cases.
  bench_result r;
  bool out_of_memory = false;
  try {
    r = run_bench(s, setting, truth);
  } catch (const std::bad_alloc&) {
    r = {};
    r.error = "out of memory (at " + std::to_string(int(status_mib("VmHWM"))) + " MiB peak)";
    out_of_memory = true;
  } catch (const std::exception& e) {
    r = {};
    r.error = std::string("the run failed: ") + e.what();
  }
  // A point that should have been measured and was not (pictures of
  // different sizes, every pixel left out) fails the run rather than
  // vanishing from the plots.
  if (setting.measure_error && r.error.empty())
    for (const bench_curve& curve : r.curves)
      for (const bench_point& p : curve.points)
        if (!std::isfinite(p.error)) r.error = curve.method + ": an error that should be measured is not finite";
  json curves = json::array();
  for (const bench_curve& curve : r.curves) {
    json points = json::array();
    for (const bench_point& p : curve.points) points.push_back(point_json(p));
    const std::size_t plus = curve.method.find(" + ");
    curves.push_back({{"label", curve_label(c, curve.method)},
                      {"method", plus == std::string::npos ? curve.method : "two-pass"},
                      {"points", points}});
  }
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json j = {{"index", index},
            {"scene", c.scene},
            {"truth", truth.exact == exact_kind::none ? "path-traced picture" : "closed form"},
            {"solver", solver_name(c)},
            {"method", method_label(c)},
            {"threads", threads},
            {"triangles", triangle_count(s)},
            {"thread_limit", c.threads},
            {"until", c.settings.stop.remaining},
            {"time_limit", c.settings.stop.seconds},
            {"link_tolerance", c.settings.link_tolerance},
            {"links", r.links},
            {"final_link_tolerance", number(r.link_tolerance)},
            {"links_final", r.links_final},
            {"shadow_rays", c.settings.form_factors.shadow_rays},
            {"hemicube_resolution", c.settings.form_factors.hemicube_resolution},
            {"max_edge", c.settings.max_edge},
            {"patch_edge", c.settings.patch_edge},
            {"adaptive_tolerance", c.settings.adaptive.enabled ? c.settings.adaptive.tolerance : 0.0},
            {"growth", c.growth},
            {"elements", r.elements},
            {"vertices", r.vertices},
            {"patches", r.patches},
            {"start_mib", start_mib},
            {"peak_mib", status_mib("VmHWM")},
            {"setup_seconds", r.setup_seconds},
            {"first_picture_seconds", number(r.first_picture_seconds)},
            {"seconds_per_step", number(r.seconds_per_step)},
            {"error", r.error},
            {"out_of_memory", out_of_memory},
            {"curves", curves}};
  const fs::path file = fs::path(out_dir) / "cases" / (std::to_string(index) + ".json");
  if (std::string e; !write_file(file.string(), j.dump() + "\n", e)) {
    std::cerr << "error: " << e << "\n";
    return exit_input_error;
  }
  return exit_ok;
}

struct child_usage {
  int status = -1;
  double wall_seconds = 0.0, cpu_seconds = 0.0, peak_mib = 0.0;
};

// Runs `bounce bench ... --run-case N` and waits for it: its own wall time,
// CPU time (all threads) and peak resident memory.
child_usage run_child(const std::vector<std::string>& args) {
  child_usage u;
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, "/proc/self/exe", nullptr, nullptr, argv.data(), environ) != 0) return u;
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) return u;
  u.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  u.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  u.cpu_seconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  u.peak_mib = double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
  return u;
}

// Why a child failed, for the report.
std::string failure_of(const child_usage& u) {
  if (u.status < 0) return "the run could not be started";
  if (u.status == 128 + SIGKILL)
    return "the run was killed (signal 9, at " + std::to_string(int(u.peak_mib)) +
           " MiB peak: out of memory, most likely)";
  if (u.status > 128) return "the run ended on signal " + std::to_string(u.status - 128);
  return "the run failed (exit status " + std::to_string(u.status) + ")";
}

}  // namespace

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

void add_bench_options(CLI::App& command, bench_options& options) {
  CLI::Option* suite =
      command
          .add_option(
              "--suite", options.suite,
              "quick: every method once, under 2 minutes; full: under 20; adaptive: adaptive vs uniform meshes "
              "(Cornell box); scale: procedural scenes of 10k to 1M triangles, hierarchical vs progressive; rays: "
              "the ray core's rays/s against Embree's own on the same rays; walkthrough: 50 views through "
              "box-room-60 and interior-1m, radiosity solved once against the path tracer per view "
              "(walkthrough-quick: 3 views of box-room-10)")
          ->check(CLI::IsMember({"quick", "full", "adaptive", "scale", "hierarchical", "clutter", "rays", "walkthrough",
                                 "walkthrough-quick"}))
          ->capture_default_str();
  command.add_option("--out", options.out_dir, "folder for the results and the cached reference pictures")
      ->capture_default_str();
  command
      .add_flag("--report-only", options.report_only,
                "write the CSV, plots and Markdown again from the folder's bench.json; run nothing")
      ->excludes(suite);  // the suite is the one bench.json holds
  command
      .add_option("--threads", options.threads,
                  "threads each run may use (tbb::global_control); 0: every core. A case of the suite that sets "
                  "its own (the scale suite's thread comparison) keeps it")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  command.add_option("--run-case", options.run_case, "internal: run one case of the suite in this process")->group("");
}

int run_bench_command(const bench_options& options) {
  if (options.suite == "rays") return run_ray_bench(options);  // one process, no cases
  if (is_walkthrough_suite(options.suite)) return run_walkthrough_bench(options);
  const suite_plan plan = make_suite(options.suite);
  if (options.run_case >= 0) {
    if (options.run_case >= int(plan.cases.size())) {
      std::cerr << "error: --run-case " << options.run_case << ": the " << options.suite << " suite has "
                << plan.cases.size() << " cases\n";
      return exit_usage;
    }
    return run_one_case(plan, options.run_case, options);
  }
  if (options.report_only) {
    const fs::path json_path = fs::path(options.out_dir) / "bench.json";
    std::ifstream in(json_path);
    const json results = json::parse(in, nullptr, false);
    if (!in || results.is_discarded() || !results.contains("cases")) {
      std::cerr << "error: " << json_path.string() << ": not a bench.json written by bounce bench\n";
      return exit_input_error;
    }
    std::cout << write_bench_report(results, options.out_dir) << "\n";
    return exit_ok;
  }
  std::error_code ec;
  fs::create_directories(fs::path(options.out_dir) / "cases", ec);
  fs::create_directories(fs::path(options.out_dir) / "reference", ec);
  if (ec) {
    std::cerr << "error: " << options.out_dir << ": " << ec.message() << "\n";
    return exit_input_error;
  }
  const auto start = std::chrono::steady_clock::now();
  json results = {{"suite", options.suite},
                  {"machine", {{"cpu", cpu_model()}, {"threads", std::thread::hardware_concurrency()}}},
                  {"picture_size", plan.picture_size},
                  {"reference_spp", plan.reference_spp},
                  {"references", json::array()},
                  {"cases", json::array()}};
  if (!prepare_references(plan, options.out_dir, results["references"])) return exit_input_error;

  int failures = 0;
  for (std::size_t i = 0; i < plan.cases.size(); ++i) {
    const bench_case& c = plan.cases[i];
    std::printf("bench: [%zu/%zu] %-22s %-12s %-8s edge %-6g%s ...", i + 1, plan.cases.size(), c.scene.c_str(),
                solver_name(c).c_str(), method_label(c).c_str(), c.settings.max_edge,
                c.threads > 0 ? (" threads " + std::to_string(c.threads)).c_str() : "");
    std::fflush(stdout);
    std::vector<std::string> args = {"bounce", "bench",         "--suite",    options.suite,
                                     "--out",  options.out_dir, "--run-case", std::to_string(i)};
    if (options.threads > 0) args.insert(args.end(), {"--threads", std::to_string(options.threads)});
    const child_usage usage = run_child(args);
    json j;
    const fs::path file = fs::path(options.out_dir) / "cases" / (std::to_string(i) + ".json");
    if (usage.status == 0) {
      std::ifstream in(file);
      j = json::parse(in, nullptr, false);
    }
    // Running out of memory is a measurement (the scene does not fit on
    // this machine), reported like the others; any other failure fails the bench.
    const bool killed = usage.status == 128 + SIGKILL;  // the kernel's OOM killer, most likely
    if (usage.status != 0 || j.is_discarded()) {
      if (!killed) ++failures;
      j = {{"index", i},
           {"scene", c.scene},
           {"solver", solver_name(c)},
           {"method", method_label(c)},
           {"max_edge", c.settings.max_edge},
           {"link_tolerance", c.settings.link_tolerance},
           {"thread_limit", c.threads},
           {"growth", c.growth},
           {"elements", 0},
           {"error", failure_of(usage)},
           {"out_of_memory", killed},
           {"curves", json::array()}};
    } else if (!j["error"].get<std::string>().empty() && c.kind != bench_solver::reference &&
               !j.value("out_of_memory", false)) {
      ++failures;  // only the matrix solver may decline a run (a mesh too large for it)
    }
    j["wall_seconds"] = usage.wall_seconds;
    j["cpu_seconds"] = usage.cpu_seconds;
    // The child's own peak (VmHWM); wait4's figure only when the child could not say.
    if (!j.contains("peak_mib")) j["peak_mib"] = usage.peak_mib;
    j["run_mib"] = j["peak_mib"].get<double>() - j.value("start_mib", 0.0);  // what the run itself took
    std::printf(" %6.2f s, %6.1f MiB%s\n", usage.wall_seconds, j["peak_mib"].get<double>(),
                j["error"].get<std::string>().empty() ? "" : ("  (" + j["error"].get<std::string>() + ")").c_str());
    results["cases"].push_back(j);
  }
  results["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const fs::path json_path = fs::path(options.out_dir) / "bench.json";
  if (std::string e; !write_file(json_path.string(), results.dump(1) + "\n", e)) std::cerr << "error: " << e << "\n";
  const std::string markdown = write_bench_report(results, options.out_dir);
  std::cout << "\n" << markdown << "\n";
  std::printf("bench: %zu runs in %.1f s; results in %s (bench.json, bench.csv, bench.md, one SVG plot per scene)\n",
              plan.cases.size(), results["seconds"].get<double>(), options.out_dir.c_str());
  if (failures) {
    std::fprintf(stderr, "error: %d run(s) failed; see bench.json\n", failures);
    return exit_input_error;
  }
  return exit_ok;
}

}  // namespace bounce
