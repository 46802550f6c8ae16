#include "viewer/bake_action.h"

#include <cstdio>
#include <filesystem>

#include "radiosity/bake.h"
#include "viewer/user_files.h"

namespace bounce {

std::string bake_shown_solution(const worker_view& view, std::string path, double exposure) {
  if (!view.source || !view.mesh || !view.solution || view.solution->radiosity.size() != view.mesh->vertex_count())
    return "bake: no solution to bake yet";
  if (path.empty()) path = dated_file_name(view.source->source, "baked", ".glb");
  bake_settings settings;
  settings.exposure = exposure;
  std::string error;
  double used = 0.0;
  if (!write_bake(path, *view.source, *view.mesh, *view.solution, settings, error, &used)) return "bake: " + error;
  char text[64];
  std::snprintf(text, sizeof text, " (exposure %.3g)", used);
  return "baked: " + std::filesystem::absolute(path).string() + text;
}

}  // namespace bounce
