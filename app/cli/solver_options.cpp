#include "cli/solver_options.h"

#include <cmath>
#include <limits>
#include <map>

#include <CLI/CLI.hpp>

#include "cli/option_values.h"

namespace bounce {

void add_solver_options(CLI::App& command, solver_settings& o) {
  std::map<std::string, solver_method> solvers;
  for (const auto& m : solver_method_names()) solvers.emplace(std::string(m.name), m.method);
  command.add_option("--solver", o.method, "radiosity solver")
      ->transform(CLI::CheckedTransformer(solvers, CLI::ignore_case))
      ->default_str(std::string(name_of(o.method)));
  command
      .add_option("--link-tolerance", o.link_tolerance,
                  "hierarchical: power a link may carry unrefined, a fraction of the power leaving all surfaces")
      ->check(number_in(0.0, 1.0, true))
      ->capture_default_str();
  command
      .add_option("--mirror-depth", o.form_factors.mirror_depth,
                  "planar mirrors a transfer may pass, one after another (hierarchical: links through chains "
                  "of them; progressive: mirror images); 0: planar mirrors are traced like curved ones")
      ->check(CLI::Range(0, max_mirror_depth))
      ->capture_default_str();
  std::map<std::string, form_factor_method> methods;
  for (const auto& m : form_factor_method_names()) methods.emplace(std::string(m.name), m.method);
  command.add_option("--method", o.form_factors.method, "form-factor method")
      ->transform(CLI::CheckedTransformer(methods, CLI::ignore_case))
      ->default_str(std::string(name_of(o.form_factors.method)));
  command
      .add_option("--max-edge", o.max_edge,
                  "longest element edge, scene units (default: diagonal/10, split while solving; progressive: /24)")
      ->check(number_in(0.0, INFINITY, true));
  command
      .add_option("--until", o.stop.remaining,
                  "stop when the remaining fraction of the power falls below this (hierarchical: the residual, "
                  "once the links are final; progressive: the unshot power)")
      ->check(number_in(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--max-steps", o.stop.max_steps,
                  "stop after this many steps (hierarchical: its steps; progressive: shots); 0: no limit")
      ->check(count_at_most(std::numeric_limits<std::uint64_t>::max()));
  command
      .add_option("--time", o.stop.seconds,
                  "stop this many seconds after the command's start: loading and meshing count, and a link "
                  "refinement still running then stops splitting; if loading and meshing alone take longer, the "
                  "command stops there with exit 1 and writes nothing (0: no limit)")
      ->check(number_in(0.0, INFINITY));
  command
      .add_option("--patch-edge", o.patch_edge,
                  "size of the shooting patches over the elements (substructuring); default 4 x max edge, "
                  "0: every element shoots (exact)")
      ->check(number_in(0.0, INFINITY));
  command.add_flag_callback(
      "--full-rays", [&o] { o.form_factors.adaptive_rays = false; },
      "raycast: cast every shadow ray, without the 2x2 visibility probe");
  command
      .add_option("--rays", o.form_factors.shadow_rays,
                  "raycast: shadow rays per receiver and shooter (rounded up to a square)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command.add_option("--hemicube", o.form_factors.hemicube_resolution, "hemicube: resolution of the top face")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  CLI::Option* adaptive =
      command.add_flag("--adaptive", o.adaptive.enabled,
                       "adaptive meshing: refine at contacts and near emitters, then where the radiosity changes "
                       "and along shadow edges while solving");
  command
      .add_option("--tolerance", o.adaptive.tolerance,
                  "adaptive: split where vertex radiosities differ by this fraction")
      ->check(number_in(0.0, INFINITY, true))
      ->capture_default_str()
      ->needs(adaptive);
  command
      .add_option("--min-edge", o.min_edge,
                  "hierarchical and --adaptive: elements whose longest edge is at most this are not split "
                  "(default: max edge / 8)")
      ->check(number_in(0.0, INFINITY, true));
  command.add_flag("--shadow-outlines", o.shadow_outlines,
                   "cut the umbra and penumbra outlines of the strong area lights into the mesh (sharp shadows of "
                   "small lights; see docs/radiosity.md)");
}

void add_view_independent_option(CLI::App& command, bool& view_independent) {
  command.add_flag("--view-independent", view_independent,
                   "hierarchical: refine every part of the scene alike; by default the camera leads refinement "
                   "(importance): what the picture shows first, the rest only as far as it lights it");
}

std::string check_view_independent_option(const CLI::App& command, const solver_settings& settings) {
  if (command.count("--view-independent") && settings.method != solver_method::hierarchical)
    return "--view-independent applies to --solver hierarchical only";
  return {};
}

std::span<const char* const> solver_option_names() {
  static constexpr const char* names[] = {"--solver",     "--link-tolerance", "--mirror-depth", "--method",
                                          "--max-edge",   "--until",          "--max-steps",    "--time",
                                          "--patch-edge", "--full-rays",      "--rays",         "--hemicube",
                                          "--adaptive",   "--tolerance",      "--min-edge",     "--shadow-outlines"};
  return names;
}

std::string check_solver_options(const CLI::App& command, solver_settings& settings) {
  // Options of the progressive solver choose it, unless the hierarchical
  // one was asked for by name: then they would be ignored.
  static constexpr const char* progressive_only[] = {"--method",   "--patch-edge", "--full-rays", "--rays",
                                                     "--hemicube", "--adaptive",   "--tolerance"};
  if (const std::string given = given_options(command, progressive_only); !given.empty()) {
    if (command.count("--solver") && settings.method == solver_method::hierarchical)
      return given + (given.find(',') == std::string::npos ? " applies" : " apply") + " to --solver progressive only";
    settings.method = solver_method::progressive;
  }
  if (settings.method != solver_method::hierarchical && command.count("--link-tolerance"))
    return "--link-tolerance applies to --solver hierarchical only";
  if (settings.method == solver_method::progressive && !settings.adaptive.enabled && command.count("--min-edge"))
    return "--min-edge applies to --solver hierarchical or --adaptive only";
  const bool hemicube = settings.form_factors.method == form_factor_method::hemicube;
  if (hemicube && command.count("--rays")) return "--rays applies to --method raycast only";
  if (hemicube && command.count("--full-rays")) return "--full-rays applies to --method raycast only";
  if (!hemicube && command.count("--hemicube")) return "--hemicube applies to --method hemicube only";
  return {};
}

}  // namespace bounce
