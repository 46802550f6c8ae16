// `bounce bench`: speed against error. Runs a suite of scenes x methods x
// mesh densities, each run in a child process of its own (so its wall time,
// CPU time and peak memory are its own), and writes CSV, JSON, an SVG plot
// per scene and a Markdown report into the output folder.
#pragma once

#include <string>

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

// Runs the suite (or one case of it, or the report alone). Not run_bench:
// measure/bench.h's run_bench is the run of one case.
int run_bench_command(const bench_options& options);

}  // namespace bounce
