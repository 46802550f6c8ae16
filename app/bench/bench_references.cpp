#include "bench/bench_references.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include <nlohmann/json.hpp>

#include "image/image.h"

namespace bounce {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path reference_path(const std::string& out_dir, const std::string& scene, int size, int spp) {
  return fs::path(out_dir) / "reference" /
         (scene + "-" + std::to_string(size) + "px-" + std::to_string(spp) + "spp.pfm");
}

bool cache_reference(const fs::path& path, const image& reference) {
  const fs::path partial = path.string() + ".partial";
  std::string error;
  if (!write_pfm(partial.string(), reference, error)) {
    std::cerr << "error: " << error << "\n";
    return false;
  }
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) {
    std::cerr << "error: " << path.string() << ": " << ec.message() << "\n";
    return false;
  }
  return true;
}

bool prepare_references(const suite_plan& plan, const std::string& out_dir, json& notes) {
  std::vector<std::string> done;
  for (const bench_case& c : plan.cases) {
    if (c.growth || find_scene(c.scene).exact != exact_kind::none) continue;
    if (std::find(done.begin(), done.end(), c.scene) != done.end()) continue;
    done.push_back(c.scene);
    const fs::path path = reference_path(out_dir, c.scene, plan.picture_size, plan.reference_spp);
    json note = {{"scene", c.scene}, {"file", path.string()}, {"spp", plan.reference_spp}, {"size", plan.picture_size}};
    if (fs::exists(path)) {
      std::cout << "bench: reference " << path.string() << " (cached)\n";
      note["cached"] = true;
    } else {
      scene s;
      std::string error;
      if (!load_bench_scene(c, plan.picture_size, s, error)) {
        std::cerr << "error: " << error << "\n";
        return false;
      }
      std::cout << "bench: path tracing the reference of " << c.scene << " (" << plan.picture_size << "x"
                << plan.picture_size << ", " << plan.reference_spp << " spp) ..." << std::flush;
      const auto start = std::chrono::steady_clock::now();
      const image reference = path_reference(s, plan.reference_spp, 1);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::cout << " " << seconds << " s\n";
      if (!cache_reference(path, reference)) return false;
      note["cached"] = false;
      note["seconds"] = seconds;
    }
    notes.push_back(note);
  }
  return true;
}

}  // namespace bounce
