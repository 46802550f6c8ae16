// The bench's report: CSV (one row per measured point), an SVG plot of
// error against time per scene, and a Markdown summary with the Pareto
// front, the targets of issue #6 and the growth with element count.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace bounce {

// The report from the collected results (bench.json's contents): CSV,
// SVG plots and Markdown, written into `out_dir`. Returns the Markdown.
std::string write_bench_report(const nlohmann::json& results, const std::string& out_dir);

}  // namespace bounce
