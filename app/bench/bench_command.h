// `bounce bench`: speed against error. Runs a suite of scenes x methods x
// mesh densities, each run in a child process of its own (so its wall time,
// CPU time and peak memory are its own), and writes CSV, JSON, an SVG plot
// per scene and a Markdown report into the output folder.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace CLI {
class App;
}

namespace bounce {

struct bench_options {
  std::string suite = "quick";  // quick (under 2 minutes) | full (under 20) | adaptive | scale | hierarchical | rays
  std::string out_dir = "bench-out";
  bool report_only = false;  // rewrite the report from out_dir/bench.json, run nothing
  int threads = 0;           // thread limit of every run (tbb::global_control); 0: every core
  int run_case = -1;         // internal: run this case of the suite in this process
};

void add_bench_options(CLI::App& command, bench_options& options);

// The CPU's model name from /proc/cpuinfo ("unknown" if absent), for reports.
std::string cpu_model();
int run_bench_command(const bench_options& options);

// The report from the collected results (bench.json's contents): CSV,
// SVG plots and Markdown, written into `out_dir`. Returns the Markdown.
std::string write_bench_report(const nlohmann::json& results, const std::string& out_dir);

}  // namespace bounce
