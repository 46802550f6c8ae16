#include "cli/info_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "base/memory_room.h"
#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "common/exit_code.h"
#include "radiosity/memory_estimate.h"
#include "scene/scene_info.h"
#include "trace/back_faces.h"

namespace bounce {
namespace {

std::string format_vec3(const vec3& v) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
  return buffer;
}

}  // namespace

void add_info_options(CLI::App& command, info_options& options) {
  add_scene_argument(command, options.scene);
  command.add_flag("--json", options.as_json, "machine-readable output");
  command.add_option("--max-edge", options.max_edge, "tessellation size for curved surfaces")
      ->check(number_in(0.0, INFINITY, true));
}

int run_info(const info_options& options) {
  scene s;
  if (int code = load_for_command(options.scene, nullptr, s); code != exit_ok) return code;
  // Curved surfaces tessellated as the default solver (hierarchical) and
  // the window mesh them, unless a size is asked for.
  double edge = options.max_edge > 0.0 ? options.max_edge : hierarchical_max_edge(s);
  scene_summary sum;
  if (std::string e = summarize_scene(s, edge, sum); !e.empty()) {
    std::cerr << "error: " << s.source << ": " << e << "\n";
    return exit_input_error;
  }
  // Checked on the scene's camera: a view of mostly back faces is black.
  const double back_faces = back_face_fraction(s, s.view, ray_scene(s));
  if (const std::string w = back_face_warning(back_faces); !w.empty())
    std::cerr << "warning: " << s.source << ": " << w << "\n";
  // What a solve with the default settings (and --max-edge) will need.
  solver_settings settings;
  settings.max_edge = options.max_edge;
  const solve_memory need = estimate_solve_memory(s, settings);
  const memory_room room = available_memory();
  if (options.as_json) {
    nlohmann::json j = {
        {"memory",
         {{"elements", need.elements},
          {"max_edge", need.max_edge},
          {"solve_bytes", need.bytes},
          {"link_bytes_max", need.link_bytes},
          {"available_bytes", std::isfinite(room.bytes) ? nlohmann::json(room.bytes) : nlohmann::json()},
          {"available_bound", room.bound}}},
        {"back_face_fraction", back_faces},
        {"scene", s.source},
        {"surfaces", sum.surfaces},
        {"polygon_meshes", sum.polygon_meshes},
        {"spheres", sum.spheres},
        {"quadrics", sum.quadrics},
        {"bezier_surfaces", sum.bezier_surfaces},
        {"bspline_surfaces", sum.bspline_surfaces},
        {"polygons", sum.polygons},
        {"patches", sum.patches},
        {"triangles", sum.triangles},
        {"max_edge", sum.max_edge},
        {"element_size", {{"hierarchical", hierarchical_max_edge(s)}, {"progressive", default_max_edge(s)}}},
        {"materials", sum.materials},
        {"textures", sum.textures},
        {"emitting_materials", sum.emitting_materials},
        {"emitting_surfaces", sum.emitting_surfaces},
        {"point_lights", sum.point_lights},
        {"spot_lights", sum.spot_lights},
        {"suns", sum.suns},
        {"sky", sum.sky},
        {"bounds",
         {{"min", {sum.bounds.min.x, sum.bounds.min.y, sum.bounds.min.z}},
          {"max", {sum.bounds.max.x, sum.bounds.max.y, sum.bounds.max.z}}}},
        {"camera",
         {{"eye", {s.view.eye.x, s.view.eye.y, s.view.eye.z}},
          {"target", {s.view.target.x, s.view.target.y, s.view.target.z}},
          {"up", {s.view.up.x, s.view.up.y, s.view.up.z}},
          {"fov", s.view.fov_y_degrees},
          {"size", {s.view.width, s.view.height}}}},
    };
    std::cout << j.dump(2) << "\n";
    return exit_ok;
  }
  std::cout << "scene:      " << s.source << "\n"
            << "surfaces:   " << sum.surfaces << " (polygon meshes " << sum.polygon_meshes << ", spheres "
            << sum.spheres << ", quadrics " << sum.quadrics << ", Bezier " << sum.bezier_surfaces << ", B-spline "
            << sum.bspline_surfaces << ")\n"
            << "polygons:   " << sum.polygons << "\n"
            << "patches:    " << sum.patches << " (Bezier patches + B-spline spans)\n"
            << "triangles:  " << sum.triangles << " (curved surfaces tessellated at max edge " << sum.max_edge << ")\n"
            << "element size: " << hierarchical_max_edge(s) << " (longest edge, scene units) to start (hierarchical, "
            << "the default; split where the light needs it), " << default_max_edge(s) << " with --solver progressive\n"
            << "materials:  " << sum.materials << " (" << sum.emitting_materials << " emitting), textures "
            << sum.textures << "\n"
            << "emitters:   " << sum.emitting_surfaces << " surface(s), " << sum.point_lights << " point light(s)"
            << (sum.spot_lights ? ", " + std::to_string(sum.spot_lights) + " spot light(s)" : "")
            << (sum.suns ? ", " + std::to_string(sum.suns) + " sun(s)" : "") << (sum.sky ? ", a sky" : "") << "\n"
            << "bounds:     " << format_vec3(sum.bounds.min) << " to " << format_vec3(sum.bounds.max) << "\n"
            << "camera:     eye " << format_vec3(s.view.eye) << ", target " << format_vec3(s.view.target) << ", fov "
            << s.view.fov_y_degrees << ", " << s.view.width << "x" << s.view.height << "\n"
            << "memory:     at least " << format_bytes(need.bytes) << " to solve (" << describe(need)
            << "), links up to " << format_bytes(need.link_bytes) << " more; " << format_bytes(room.bytes)
            << " available (" << room.bound << ")\n";
  return exit_ok;
}

}  // namespace bounce
