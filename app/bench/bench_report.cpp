#include "bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/whole_file.h"
#include "measure/bench.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

double number(const json& j) {
  return j.is_number() ? j.get<double>() : not_measured;
}

std::string format(const char* fmt, double v) {
  if (!std::isfinite(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, v);
  return buffer;
}

std::string percent(double v) {
  if (!std::isfinite(v)) return "-";
  return v < 1e-4 ? format("%.1e", v * 100.0) + "%" : format("%.3g", v * 100.0) + "%";
}

bench_curve to_curve(const json& c) {
  bench_curve curve;
  curve.method = c["method"].get<std::string>();
  for (const json& p : c["points"]) {
    bench_point q;
    q.seconds = number(p["seconds"]);
    q.error = number(p["error"]);
    curve.points.push_back(q);
  }
  return curve;
}

// Every curve of every (non-growth) case of a scene, in suite order.
struct scene_curves {
  std::vector<const json*> cases;   // per curve
  std::vector<const json*> curves;  // the curve's JSON
};

std::map<std::string, scene_curves> curves_by_scene(const json& results) {
  std::map<std::string, scene_curves> out;
  for (const json& c : results["cases"]) {
    if (c.value("growth", false)) continue;
    for (const json& curve : c["curves"]) {
      auto& s = out[c["scene"].get<std::string>()];
      s.cases.push_back(&c);
      s.curves.push_back(&curve);
    }
  }
  return out;
}

// Pareto flags per point, per curve of one scene; with `radiosity_only`,
// the front among the radiosity methods alone (what their defaults are
// chosen from), the path tracer's points left out.
std::vector<std::vector<bool>> front_of(const scene_curves& sc, bool radiosity_only = false) {
  std::vector<double> t, e;
  for (const json* curve : sc.curves)
    for (const json& p : (*curve)["points"]) {
      const bool left_out = radiosity_only && (*curve)["method"] == "path";
      t.push_back(number(p["seconds"]));
      e.push_back(left_out ? not_measured : number(p["error"]));
    }
  const std::vector<bool> flags = pareto_front(t, e);
  std::vector<std::vector<bool>> out;
  std::size_t k = 0;
  for (const json* curve : sc.curves) {
    out.emplace_back();
    for (std::size_t i = 0; i < (*curve)["points"].size(); ++i) out.back().push_back(flags[k++]);
  }
  return out;
}

// Text that becomes `path` whole when it goes out of scope (every way out
// of the writers below), or an error on standard error.
struct report_file {
  std::string path;
  std::ostringstream out;
  ~report_file() {
    if (std::string e; !write_file(path, out.str(), e)) std::cerr << "error: " << e << "\n";
  }
};

void write_csv(const json& results, const std::string& out_dir) {
  report_file file{(fs::path(out_dir) / "bench.csv").string(), {}};
  std::ostringstream& out = file.out;
  out << "scene,curve,method,solver,shadow_rays,hemicube_resolution,max_edge,patch_edge,elements,vertices,patches,"
         "run_wall_seconds,run_cpu_seconds,peak_mib,seconds,cpu_seconds,steps,rays,remaining,error,max_error,"
         "power_error,balance_error,residual,pareto\n";
  const auto by_scene = curves_by_scene(results);
  std::map<const json*, std::vector<bool>> fronts;
  for (const auto& [name, sc] : by_scene) {
    const auto f = front_of(sc);
    for (std::size_t i = 0; i < sc.curves.size(); ++i) fronts[sc.curves[i]] = f[i];
  }
  auto cell = [](const json& j) -> std::string {
    if (j.is_null()) return "";
    if (j.is_string()) return "\"" + j.get<std::string>() + "\"";
    return j.dump();
  };
  for (const json& c : results["cases"]) {
    for (const json& curve : c["curves"]) {
      const auto& flags = fronts[&curve];
      std::size_t i = 0;
      for (const json& p : curve["points"]) {
        out << cell(c["scene"]) << "," << cell(curve["label"]) << "," << cell(curve["method"]) << ","
            << cell(c["solver"]) << "," << cell(c["shadow_rays"]) << "," << cell(c["hemicube_resolution"]) << ","
            << cell(c["max_edge"]) << "," << cell(c["patch_edge"]) << "," << cell(c["elements"]) << ","
            << cell(c["vertices"]) << "," << cell(c["patches"]) << "," << cell(c["wall_seconds"]) << ","
            << cell(c["cpu_seconds"]) << "," << cell(c["peak_mib"]) << "," << cell(p["seconds"]) << ","
            << cell(p["cpu_seconds"]) << "," << cell(p["steps"]) << "," << cell(p["rays"]) << ","
            << cell(p["remaining"]) << "," << cell(p["error"]) << "," << cell(p["max_error"]) << ","
            << cell(p["power_error"]) << "," << cell(p["balance_error"]) << "," << cell(p.value("residual", json()))
            << "," << (i < flags.size() && flags[i] ? 1 : 0) << "\n";
        ++i;
      }
    }
  }
}

// Error against time, log-log, one polyline per curve, the Pareto front's
// points ringed.
void write_svg(const std::string& scene, const scene_curves& sc, const std::string& error_name,
               const std::string& path) {
  constexpr double width = 900, height = 520, left = 70, right = 330, top = 40, bottom = 50;
  constexpr double floor = 1e-7;  // errors below this (exact to round-off) are drawn on the floor
  double t_lo = 1e300, t_hi = 0, e_lo = 1e300, e_hi = 0;
  for (const json* curve : sc.curves)
    for (const json& p : (*curve)["points"]) {
      const double t = number(p["seconds"]), e = number(p["error"]);
      if (!(t > 0) || std::isnan(e)) continue;
      t_lo = std::min(t_lo, t);
      t_hi = std::max(t_hi, t);
      e_lo = std::min(e_lo, std::max(e, floor));
      e_hi = std::max(e_hi, std::max(e, floor));
    }
  report_file file{path, {}};
  std::ostringstream& out = file.out;
  out << std::fixed << std::setprecision(1);  // coordinates to a tenth of a pixel: small files
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out << "<text x=\"" << left << "\" y=\"24\" font-size=\"15\">" << scene << ": " << error_name
      << " against time (log-log)</text>\n";
  if (t_hi <= 0) {
    out << "<text x=\"" << left << "\" y=\"80\">no measured points</text>\n</svg>\n";
    return;
  }
  const double lt0 = std::floor(std::log10(t_lo)), lt1 = std::max(std::ceil(std::log10(t_hi)), lt0 + 1);
  const double le0 = std::floor(std::log10(e_lo)), le1 = std::max(std::ceil(std::log10(e_hi)), le0 + 1);
  const double pw = width - left - right, ph = height - top - bottom;
  auto x_of = [&](double t) { return left + (std::log10(t) - lt0) / (lt1 - lt0) * pw; };
  auto y_of = [&](double e) { return top + (le1 - std::log10(std::max(e, floor))) / (le1 - le0) * ph; };
  out << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"#888\"/>\n";
  for (double d = lt0; d <= lt1; ++d) {
    const double x = x_of(std::pow(10.0, d));
    out << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << top + ph
        << "\" stroke=\"#ddd\"/><text x=\"" << x << "\" y=\"" << top + ph + 16 << "\" text-anchor=\"middle\">"
        << format("%g", std::pow(10.0, d)) << "</text>\n";
  }
  for (double d = le0; d <= le1; ++d) {
    const double y = y_of(std::pow(10.0, d));
    out << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + pw << "\" y2=\"" << y
        << "\" stroke=\"#ddd\"/><text x=\"" << left - 6 << "\" y=\"" << y + 4 << "\" text-anchor=\"end\">"
        << format("%g", std::pow(10.0, d)) << "</text>\n";
  }
  out << "<text x=\"" << left + pw / 2 << "\" y=\"" << height - 12 << "\" text-anchor=\"middle\">seconds</text>\n";
  out << "<text transform=\"translate(16," << top + ph / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << error_name
      << "</text>\n";
  static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
                                  "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000", "#aec7e8"};
  const auto fronts = front_of(sc);
  for (std::size_t i = 0; i < sc.curves.size(); ++i) {
    const json& curve = *sc.curves[i];
    const char* colour = colours[i % std::size(colours)];
    const bool dashed = curve["method"] == "two-pass" || curve["method"] == "path";
    std::ostringstream points;
    std::size_t k = 0;
    for (const json& p : curve["points"]) {
      const double t = number(p["seconds"]), e = number(p["error"]);
      if (t > 0 && !std::isnan(e)) {
        points << x_of(t) << "," << y_of(e) << " ";
        out << "<circle cx=\"" << x_of(t) << "\" cy=\"" << y_of(e) << "\" r=\"" << (fronts[i][k] ? 4 : 2)
            << "\" fill=\"" << (fronts[i][k] ? "none" : colour) << "\" stroke=\"" << colour << "\"/>\n";
      }
      ++k;
    }
    out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\""
        << (dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"" << points.str() << "\"/>\n";
    const double ly = top + 14 + 15 * double(i);
    out << "<line x1=\"" << left + pw + 12 << "\" y1=\"" << ly - 4 << "\" x2=\"" << left + pw + 36 << "\" y2=\""
        << ly - 4 << "\" stroke=\"" << colour << "\" stroke-width=\"2\"" << (dashed ? " stroke-dasharray=\"5,3\"" : "")
        << "/><text x=\"" << left + pw + 42 << "\" y=\"" << ly << "\">" << curve["label"].get<std::string>()
        << "</text>\n";
  }
  out << "<text x=\"" << left + pw + 12 << "\" y=\"" << height - 12
      << "\" fill=\"#555\">rings: on the Pareto front</text>\n</svg>\n";
}

const json& last_point(const json& curve) {
  return curve["points"].back();
}

// The last point's mean per material, as a ratio to the reference's: a
// bias (a whole ceiling dark) shows here, where one error over the picture
// mixes it with noise. Nothing when no curve measured pictures.
void surfaces_table(const scene_curves& sc, std::ostringstream& md) {
  std::vector<std::string> materials;
  for (const json* curve : sc.curves) {
    if ((*curve)["points"].empty()) continue;
    for (const json& m : last_point(*curve).value("surfaces", json::array())) {
      const std::string name = m["material"].get<std::string>();
      if (std::find(materials.begin(), materials.end(), name) == materials.end()) materials.push_back(name);
    }
  }
  if (materials.empty()) return;
  md << "\nMean radiance per material at the last point, as a ratio to the reference's (1 = unbiased):\n\n| curve |";
  for (const std::string& m : materials) md << " " << m << " |";
  md << "\n|---|";
  for (std::size_t k = 0; k < materials.size(); ++k) md << "---:|";
  md << "\n";
  for (const json* curve : sc.curves) {
    if ((*curve)["points"].empty()) continue;
    md << "| " << (*curve)["label"].get<std::string>() << " |";
    const json surfaces = last_point(*curve).value("surfaces", json::array());
    for (const std::string& name : materials) {
      const auto it =
          std::find_if(surfaces.begin(), surfaces.end(), [&](const json& m) { return m["material"] == name; });
      md << " "
         << (it == surfaces.end() || !(*it)["ratio"].is_number() ? std::string("-")
                                                                 : format("%.3f", (*it)["ratio"].get<double>()))
         << " |";
    }
    md << "\n";
  }
}

std::string error_name_of(const scene_curves& sc) {
  return sc.cases.front()->value("truth", "") == "closed form" ? "relative RMSE per vertex"
                                                               : "relative RMSE of the picture";
}

void growth_section(const json& results, std::ostringstream& md) {
  std::vector<double> elements, setup, first, per_shot, to_one_percent, memory;
  std::ostringstream rows;
  for (const json& c : results["cases"]) {
    if (!c.value("growth", false) || c["curves"].empty() || c["curves"][0]["points"].empty()) continue;
    const json& last = last_point(c["curves"][0]);
    const double n = number(c["elements"]);
    const bool reached = number(last["remaining"]) <= 0.01;
    elements.push_back(n);
    setup.push_back(number(c["setup_seconds"]));
    first.push_back(number(c["first_picture_seconds"]));
    per_shot.push_back(number(c["seconds_per_step"]));
    to_one_percent.push_back(reached ? number(last["seconds"]) : not_measured);
    memory.push_back(number(c["run_mib"]));
    rows << "| " << c["elements"].get<std::size_t>() << " | " << format("%g", number(c["max_edge"])) << " | "
         << format("%.3f", setup.back()) << " | " << format("%.3f", first.back()) << " | "
         << format("%.2e", per_shot.back()) << " | "
         << (reached ? format("%.2f", to_one_percent.back())
                     : "not in " + format("%.0f", number(last["seconds"])) + " s (" +
                           percent(number(last["remaining"])) + " left)")
         << " | " << format("%.0f", number(c["peak_mib"])) << " | " << format("%.1f", memory.back()) << " |\n";
  }
  if (elements.empty()) return;
  md << "\n## Growth with element count (Cornell box, raycast 16 rays, patches of 4x the element edge)\n\n"
     << "| elements | edge | set-up s | first picture s | s per shot | to 1% unshot s | peak MiB | run MiB |\n"
     << "|---:|---:|---:|---:|---:|---:|---:|---:|\n"
     << rows.str() << "\nFitted exponents k of time ~ elements^k (least squares in log-log over the sizes "
     << "measured): set-up " << format("%.2f", growth_exponent(elements, setup)) << ", first picture "
     << format("%.2f", growth_exponent(elements, first)) << ", time per shot "
     << format("%.2f", growth_exponent(elements, per_shot)) << ", time to 1% unshot "
     << format("%.2f", growth_exponent(elements, to_one_percent)) << " (sizes that reached it), memory of the run "
     << format("%.2f", growth_exponent(elements, memory))
     << ". Peak MiB is the process's peak resident memory; run MiB is that less the program's own at start.\n";
}

// Adaptive against uniform meshes (radiosity alone, not two-pass): the
// lowest error a uniform mesh reached, and the first point of an adaptive
// curve at or below it, with its element count and time.
void adaptive_line(const scene_curves& curves, std::ostringstream& md) {
  auto has = [](const json& curve, const char* part) {
    return curve["label"].get<std::string>().find(part) != std::string::npos;
  };
  double uniform = 1e300, uniform_time = 0.0;
  std::size_t uniform_elements = 0;
  std::string uniform_label;
  for (const json* curve : curves.curves) {
    const std::string method = (*curve)["method"].get<std::string>();
    if ((method != "raycast" && method != "hemicube") || has(*curve, "adaptive")) continue;
    for (const json& p : (*curve)["points"])
      if (number(p["error"]) < uniform) {
        uniform = number(p["error"]);
        uniform_time = number(p["seconds"]);
        uniform_elements = p.value("elements", std::size_t(0));
        uniform_label = (*curve)["label"].get<std::string>();
      }
  }
  if (!(uniform < 1e300)) return;
  const json* best = nullptr;
  const json* best_curve = nullptr;
  for (const json* curve : curves.curves) {
    if (!has(*curve, "adaptive") || has(*curve, " + two-pass")) continue;
    for (const json& p : (*curve)["points"])
      if (number(p["error"]) <= uniform) {
        if (!best || number(p["seconds"]) < number((*best)["seconds"])) {
          best = &p;
          best_curve = curve;
        }
        break;
      }
  }
  md << "- Adaptive meshing against the best uniform mesh (radiosity alone): the uniform meshes' lowest error is "
     << percent(uniform) << " (" << uniform_label << ", " << uniform_elements << " elements, "
     << format("%.3f s", uniform_time) << "); ";
  if (!best) {
    md << "no adaptive run reached it.\n";
    return;
  }
  const std::size_t elements = (*best).value("elements", std::size_t(0));
  md << "adaptive meshing reaches it in " << format("%.3f s", number((*best)["seconds"])) << " with " << elements
     << " elements (" << (*best_curve)["label"].get<std::string>()
     << "): " << format("%.2g", elements ? double(uniform_elements) / double(elements) : 0.0) << "x fewer elements, "
     << format("%.2g", uniform_time / number((*best)["seconds"])) << "x less time.\n";
}

void targets_section(const json& results, const std::map<std::string, scene_curves>& by_scene, std::ostringstream& md) {
  const auto it = by_scene.find("cornell");
  if (it == by_scene.end()) return;
  md << "\n## Targets (Cornell box, picture RMSE after 4x downsampling, light left out; path tracer at the "
        "bench's picture size)\n\n";
  for (double target : {0.05, 0.02}) {
    double best = not_measured, path = not_measured;
    std::string best_label;
    for (const json* curve : it->second.curves) {
      const double t = time_to_error(to_curve(*curve), target);
      if ((*curve)["method"] == "path") {
        path = t;
      } else if (std::isfinite(t) && !(t >= best)) {
        best = t;
        best_label = (*curve)["label"].get<std::string>();
      }
    }
    md << "- To " << percent(target) << ": best radiosity setting "
       << (std::isfinite(best) ? format("%.3f s", best) + " (" + best_label + ")" : "not reached") << "; path tracer "
       << (std::isfinite(path) ? format("%.2f s", path) : "not reached in its run");
    if (std::isfinite(best) && std::isfinite(path))
      md << "; the path tracer's time / radiosity's: " << format("%.2g", path / best);
    md << ".\n";
  }
  // The lowest error any radiosity curve reached, and what the path tracer needs for it.
  double lowest = 1e300, lowest_time = 0;
  std::string lowest_label;
  const json* path_curve = nullptr;
  for (const json* curve : it->second.curves) {
    if ((*curve)["method"] == "path") {
      path_curve = curve;
      continue;
    }
    for (const json& p : (*curve)["points"])
      if (number(p["error"]) < lowest) {
        lowest = number(p["error"]);
        lowest_time = number(p["seconds"]);
        lowest_label = (*curve)["label"].get<std::string>();
      }
  }
  if (lowest < 1e300) {
    md << "- Lowest radiosity error: " << percent(lowest) << " at " << format("%.3f s", lowest_time) << " ("
       << lowest_label << ")";
    if (path_curve) {
      const double t = time_to_error(to_curve(*path_curve), lowest);
      md << "; the path tracer reaches it in " << (std::isfinite(t) ? format("%.2f s", t) : "more than its run");
      if (std::isfinite(t)) md << " (its time / radiosity's: " << format("%.2g", t / lowest_time) << ")";
    }
    md << ".\n";
  }
  adaptive_line(it->second, md);
  // Time to the first useful picture (direct light everywhere) at about 10k elements.
  const json* nearest = nullptr;
  for (const json& c : results["cases"])
    if (c.value("growth", false) && c["first_picture_seconds"].is_number() &&
        (!nearest ||
         std::abs(std::log(number(c["elements"]) / 1e4)) < std::abs(std::log(number((*nearest)["elements"]) / 1e4))))
      nearest = &c;
  if (nearest)
    md << "- First useful picture (every emitter shot: direct light everywhere), from the loaded scene, at "
       << (*nearest)["elements"].get<std::size_t>()
       << " elements: " << format("%.3f s", number((*nearest)["first_picture_seconds"])) << " (meshing and set-up "
       << format("%.3f s", number((*nearest)["setup_seconds"])) << ").\n";
}

// Time to an error on a case's own curve (the solver alone, not two-pass),
// or "not reached".
std::string time_to(const json& c, double target) {
  if (c["curves"].empty()) return "-";
  const double t = time_to_error(to_curve(c["curves"][0]), target);
  return std::isfinite(t) ? format("%.3g", t) : "not reached";
}

// The scale suite: per procedural scene and solver, what it takes to reach
// a useful picture, how that grows with the scene, and the speed-up with threads.
void scale_section(const json& results, std::ostringstream& md) {
  if (results.value("suite", "") != "scale") return;
  md << "\n## Scale (procedural scenes; times from the built scene, meshing and set-up included; error of the "
        "solver's own picture, not two-pass)\n\n"
     << "| scene | solver | triangles | elements | first picture s | to 10% s | to 5% s | to 2% s | final error | "
        "remaining | time s | peak MiB | links |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::map<std::string, std::vector<double>> triangles, to_10, to_5;  // per solver
  for (const json& c : results["cases"]) {
    if (c.value("thread_limit", 0) > 0 || c.value("solver", "") == "path") continue;
    const std::string solver = c.value("solver", "");
    md << "| " << c["scene"].get<std::string>() << " | " << solver << " | ";
    if (!c["error"].get<std::string>().empty() || c["curves"].empty() || c["curves"][0]["points"].empty()) {
      md << "- | - | failed: " << c["error"].get<std::string>() << " | | | | | | | | |\n";
      continue;
    }
    const json& last = last_point(c["curves"][0]);
    const bench_curve curve = to_curve(c["curves"][0]);
    triangles[solver].push_back(number(c.value("triangles", json())));
    to_10[solver].push_back(time_to_error(curve, 0.1));
    to_5[solver].push_back(time_to_error(curve, 0.05));
    md << c.value("triangles", std::size_t(0)) << " | " << c["elements"].get<std::size_t>() << " | "
       << format("%.3g", number(c["first_picture_seconds"])) << " | " << time_to(c, 0.1) << " | " << time_to(c, 0.05)
       << " | " << time_to(c, 0.02) << " | " << percent(number(last["error"])) << " | "
       << percent(number(last["remaining"])) << " | " << format("%.3g", number(last["seconds"])) << " | "
       << format("%.0f", number(c["peak_mib"])) << " | "
       << (solver == "hierarchical" ? std::to_string(c.value("links", std::uint64_t(0))) : "-") << " |\n";
  }
  md << "\nFitted exponents k of time ~ triangles^k (least squares in log-log over the scenes that reached the "
        "error):";
  for (const auto& [solver, n] : triangles) {
    auto reached = [](const std::vector<double>& t) {
      return std::count_if(t.begin(), t.end(), [](double v) { return std::isfinite(v); });
    };
    auto scenes = [](std::ptrdiff_t k) { return std::to_string(k) + (k == 1 ? " scene" : " scenes"); };
    md << " " << solver << ": to 10% " << format("%.2f", growth_exponent(n, to_10[solver])) << " ("
       << scenes(reached(to_10[solver])) << "), to 5% " << format("%.2f", growth_exponent(n, to_5[solver])) << " ("
       << scenes(reached(to_5[solver])) << ");";
  }
  double reference_seconds = 0.0;
  for (const json& note : results["references"]) reference_seconds += number(note.value("seconds", json(0.0)));
  md << " '-': fewer than two scenes reached it. Peak MiB is the run's process, the picture judge's ray-tracing "
        "BVH included; remaining is the residual (hierarchical) or the unshot power (progressive) left at the end, '-' "
        "when not finite. The path-traced references took "
     << format("%.0f", reference_seconds) << " s of the suite's time (0: cached).\n";

  // The same hierarchical run on 1 and on 2 threads.
  std::vector<const json*> runs;
  for (const json& c : results["cases"])
    if (c.value("thread_limit", 0) > 0 && c["error"].get<std::string>().empty() && !c["curves"].empty() &&
        !c["curves"][0]["points"].empty())
      runs.push_back(&c);
  std::sort(runs.begin(), runs.end(),
            [](const json* a, const json* b) { return a->value("thread_limit", 0) < b->value("thread_limit", 0); });
  bool any = false;
  for (const json& c : results["cases"]) any = any || c.value("thread_limit", 0) > 0;
  if (!any) return;
  md << "\n### Threads\n\n"
     << "| scene | solver | threads | to 10% s | to 5% s | to 2% s | final error | remaining | steps | time s | "
        "cores busy | stopped |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  auto stopped = [](const json& c) {
    const json& last = last_point(c["curves"][0]);
    const bool converged = c.value("links_final", false) && number(last["remaining"]) <= number(c["until"]);
    return converged ? "at " + percent(number(c["until"])) + " remaining" : "at the time limit";
  };
  for (const json& c : results["cases"]) {
    if (c.value("thread_limit", 0) <= 0) continue;
    md << "| " << c["scene"].get<std::string>() << " | " << c.value("solver", "") << " | " << c.value("thread_limit", 0)
       << " | ";
    if (!c["error"].get<std::string>().empty() || c["curves"].empty() || c["curves"][0]["points"].empty()) {
      md << "failed: " << c["error"].get<std::string>() << " | | | | | | | | |\n";
      continue;
    }
    const json& last = last_point(c["curves"][0]);
    md << time_to(c, 0.1) << " | " << time_to(c, 0.05) << " | " << time_to(c, 0.02) << " | "
       << percent(number(last["error"])) << " | " << percent(number(last["remaining"])) << " | "
       << last["steps"].get<std::uint64_t>() << " | " << format("%.3g", number(last["seconds"])) << " | "
       << format("%.2f", number(c["cpu_seconds"]) / number(c["wall_seconds"])) << " | " << stopped(c) << " |\n";
  }
  if (runs.size() < 2) return;
  const json& one = *runs.front();
  const json& many = *runs.back();
  md << "\nSpeed-up of " << many.value("thread_limit", 0) << " threads over " << one.value("thread_limit", 0)
     << " (time on " << one.value("thread_limit", 0) << " / time on " << many.value("thread_limit", 0) << "):";
  for (double target : {0.1, 0.05, 0.02}) {
    const double a = time_to_error(to_curve(one["curves"][0]), target);
    const double b = time_to_error(to_curve(many["curves"][0]), target);
    md << " to " << percent(target) << " " << (std::isfinite(a) && std::isfinite(b) ? format("%.2fx", a / b) : "-")
       << ";";
  }
  const std::string how_one = stopped(one), how_many = stopped(many);
  const json &last_one = last_point(one["curves"][0]), &last_many = last_point(many["curves"][0]);
  md << " total time to the stopping point ";
  if (how_one == how_many && how_one != "at the time limit")
    md << format("%.2fx", number(last_one["seconds"]) / number(last_many["seconds"])) << " (both stopped " << how_one
       << ", after " << last_one["steps"].get<std::uint64_t>() << " and " << last_many["steps"].get<std::uint64_t>()
       << " steps)";
  else
    md << "- (the runs stopped " << how_one << " and " << how_many << ")";
  md << ". Times to an error are interpolated between the measured stops. Cores busy: the run's CPU time over its "
        "wall time (measuring included); below the thread count, the threads waited for each other or for the "
        "machine's other load.\n";
}

// Cases of scenes that have no curve at all (every run of the scene failed).
void failed_section(const json& results, const std::map<std::string, scene_curves>& by_scene, std::ostringstream& md) {
  std::ostringstream lines;
  for (const json& c : results["cases"])
    if (!by_scene.count(c["scene"].get<std::string>()) && !c["error"].get<std::string>().empty())
      lines << "- " << c["scene"].get<std::string>() << ", " << c.value("solver", "") << " " << c.value("method", "")
            << ": " << c["error"].get<std::string>() << "\n";
  if (!lines.str().empty()) md << "\n## Runs that failed (scenes with no measured curve)\n\n" << lines.str();
}

}  // namespace

std::string write_bench_report(const json& results, const std::string& out_dir) {
  write_csv(results, out_dir);
  const auto by_scene = curves_by_scene(results);
  std::ostringstream md;
  md << "# bounce bench: " << results["suite"].get<std::string>() << " suite\n\n"
     << "Machine: " << results["machine"]["cpu"].get<std::string>() << ", "
     << results["machine"]["threads"].get<unsigned>() << " threads. " << results["cases"].size() << " runs in "
     << format("%.0f", number(results["seconds"])) << " s. Pictures " << results["picture_size"].get<int>() << "x"
     << results["picture_size"].get<int>() << ", path-traced references at " << results["reference_spp"].get<int>()
     << " spp. Times are from the loaded scene (meshing and set-up included, measuring excluded); "
     << "'two-pass' adds the still's tracing time to the solver's. Error: relative RMSE (RMS difference / mean "
        "of the reference) per vertex against the closed form where one exists, otherwise over the picture against "
        "the path-traced reference, 4x4 blocks averaged, emitters left out. 'Pareto points': the curve's points "
        "that no other point of the scene beats on both time and error; 'of radiosity': the same among the "
        "radiosity methods alone.\n";
  for (const auto& [scene, sc] : by_scene) {
    const std::string error_name = error_name_of(sc);
    const std::string svg = scene + ".svg";
    write_svg(scene, sc, error_name, (fs::path(out_dir) / svg).string());
    md << "\n## " << scene << "\n\n![" << scene << "](" << svg << ")\n\n"
       << "| curve | elements | peak MiB | time s | error | max error | power error | to 10% s | to 5% s | to 2% s "
          "| Pareto points | of radiosity |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    const auto fronts = front_of(sc);
    const auto radiosity_fronts = front_of(sc, true);
    for (std::size_t i = 0; i < sc.curves.size(); ++i) {
      const json& c = *sc.cases[i];
      const json& curve = *sc.curves[i];
      if (curve["points"].empty()) continue;
      const json& last = last_point(curve);
      const bench_curve bc = to_curve(curve);
      md << "| " << curve["label"].get<std::string>() << " | " << c["elements"].get<std::size_t>() << " | "
         << format("%.0f", number(c["peak_mib"])) << " | " << format("%.3g", number(last["seconds"])) << " | "
         << percent(number(last["error"])) << " | " << percent(number(last["max_error"])) << " | "
         << percent(number(last["power_error"])) << " | " << format("%.3g", time_to_error(bc, 0.1)) << " | "
         << format("%.3g", time_to_error(bc, 0.05)) << " | " << format("%.3g", time_to_error(bc, 0.02)) << " | "
         << std::count(fronts[i].begin(), fronts[i].end(), true) << " | "
         << std::count(radiosity_fronts[i].begin(), radiosity_fronts[i].end(), true) << " |\n";
    }
    surfaces_table(sc, md);
    for (const json& c : results["cases"])
      if (c["scene"] == scene && !c["error"].get<std::string>().empty())
        md << "\nNot run: " << c.value("solver", "") << " " << c.value("method", "") << ", edge "
           << format("%g", number(c.value("max_edge", json()))) << ": " << c["error"].get<std::string>() << "\n";
  }
  targets_section(results, by_scene, md);
  growth_section(results, md);
  scale_section(results, md);
  failed_section(results, by_scene, md);
  if (std::string e; !write_file((fs::path(out_dir) / "bench.md").string(), md.str(), e))
    std::cerr << "error: " << e << "\n";
  return md.str();
}

}  // namespace bounce
