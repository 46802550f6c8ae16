// `bounce bench --suite walkthrough`: radiosity solved once and drawn from
// every view along a path, against the path tracer rendering each view to
// the same error (measure/walkthrough.h). One process, no child per case;
// writes walkthrough.json and walkthrough.md into the output folder.
#pragma once

#include "bench/bench_command.h"

namespace bounce {

// True for the suites run_walkthrough_bench runs.
bool is_walkthrough_suite(const std::string& suite);

int run_walkthrough_bench(const bench_options& options);

}  // namespace bounce
