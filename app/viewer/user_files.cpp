#include "viewer/user_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <fstream>

#include <nlohmann/json.hpp>

#include "scene/camera_file.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t max_recent = 10;

fs::path bookmarks_file() {
  const fs::path folder = config_folder();
  return folder.empty() ? fs::path() : folder / "bookmarks.json";
}

// Files by absolute path, so that a scene opened from elsewhere finds its bookmarks.
std::string scene_key(const std::string& source) {
  if (source.starts_with("embedded:") || source.starts_with("generated:")) return source;
  std::error_code ec;
  return fs::absolute(source, ec).lexically_normal().string();
}

nlohmann::json read_all_bookmarks() {
  std::ifstream in(bookmarks_file());
  if (!in) return nlohmann::json::object();
  nlohmann::json all = nlohmann::json::parse(in, nullptr, false);
  return all.is_object() ? all : nlohmann::json::object();
}

fs::path recent_file() {
  const fs::path folder = config_folder();
  return folder.empty() ? fs::path() : folder / "recent.txt";
}

fs::path panel_file() {
  const fs::path folder = config_folder();
  return folder.empty() ? fs::path() : folder / "panel.json";
}

}  // namespace

fs::path config_folder() {
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg) return fs::path(xdg) / "bounce";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".config" / "bounce";
  return {};
}

std::vector<std::string> find_asset_scenes(const fs::path& exe) {
  std::error_code ec;
  const fs::path self = exe.empty() ? fs::read_symlink("/proc/self/exe", ec) : exe;
  const fs::path dir = self.parent_path();
  std::vector<std::string> scenes;
  for (const fs::path& candidate :
       {dir / "assets", dir.parent_path() / "assets", dir.parent_path().parent_path() / "assets",
        dir.parent_path() / "share" / "bounce" / "assets", fs::current_path(ec) / "assets"}) {
    if (!fs::is_directory(candidate, ec)) continue;
    scenes = find_scenes(fs::weakly_canonical(candidate, ec).string());
    if (!scenes.empty()) break;
  }
  for (const char* builtin :
       {"embedded:cornell_box/cornell_box.json", "generated:box-room-60", "generated:interior-100k"})
    scenes.emplace_back(builtin);
  return scenes;
}

std::vector<std::string> read_recent_scenes() {
  std::vector<std::string> recent;
  std::ifstream in(recent_file());
  for (std::string line; recent.size() < max_recent && std::getline(in, line);)
    if (!line.empty()) recent.push_back(line);
  return recent;
}

std::vector<std::string> remember_scene(const std::string& source) {
  std::vector<std::string> recent = read_recent_scenes();
  if (source.starts_with("embedded:")) return recent;
  std::error_code ec;
  const bool named = source.starts_with("generated:");
  const std::string entry = named ? source : fs::absolute(source, ec).lexically_normal().string();
  std::erase(recent, entry);
  recent.insert(recent.begin(), entry);
  if (recent.size() > max_recent) recent.resize(max_recent);
  const fs::path file = recent_file();
  if (file.empty()) return recent;
  fs::create_directories(file.parent_path(), ec);
  std::ofstream out(file);
  for (const std::string& r : recent) out << r << "\n";
  return recent;
}

std::vector<camera_bookmark> read_bookmarks(const std::string& scene_source) {
  std::vector<camera_bookmark> out;
  const nlohmann::json all = read_all_bookmarks();
  const auto it = all.find(scene_key(scene_source));
  if (it == all.end() || !it->is_array()) return out;
  for (const nlohmann::json& entry : *it) {
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string() || !entry.contains("camera"))
      continue;
    camera_bookmark b{entry["name"].get<std::string>(), {}};
    std::string error;
    if (parse_camera_text(nlohmann::json{{"camera", entry["camera"]}}.dump(), "bookmarks.json", b.view, error))
      out.push_back(std::move(b));
  }
  return out;
}

void save_bookmarks(const std::string& scene_source, const std::vector<camera_bookmark>& bookmarks) {
  const fs::path file = bookmarks_file();
  if (file.empty()) return;
  nlohmann::json all = read_all_bookmarks();
  nlohmann::json list = nlohmann::json::array();
  for (const camera_bookmark& b : bookmarks)
    list.push_back({{"name", b.name}, {"camera", nlohmann::json::parse(camera_json(b.view))["camera"]}});
  all[scene_key(scene_source)] = list;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  std::ofstream(file) << all.dump(2) << "\n";
}

std::string dated_file_name(const std::string& scene_source, const std::string& kind, const std::string& extension) {
  std::string name = fs::path(scene_source).stem().string();
  if (scene_source.starts_with("generated:")) name = scene_source.substr(10);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  if (name.empty()) name = "bounce";
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &local);
  const std::string base = name + "-" + kind + "-" + stamp;
  std::error_code ec;
  std::string candidate = base + extension;
  for (int n = 2; fs::exists(candidate, ec); ++n) candidate = base + "-" + std::to_string(n) + extension;
  return candidate;
}

panel_layout read_panel_layout() {
  panel_layout layout;
  std::ifstream in(panel_file());
  if (!in) return layout;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object()) return layout;
  if (const auto it = j.find("visible"); it != j.end() && it->is_boolean()) layout.visible = it->get<bool>();
  if (const auto it = j.find("width"); it != j.end() && it->is_number()) {
    const double width = it->get<double>();
    if (std::isfinite(width) && width > 0.0 && width < 1e5) layout.width = float(width);
  }
  return layout;
}

void save_panel_layout(const panel_layout& layout) {
  const fs::path file = panel_file();
  if (file.empty()) return;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  const fs::path partial = file.string() + ".partial";
  {
    std::ofstream out(partial);
    out << nlohmann::json{{"visible", layout.visible}, {"width", layout.width}}.dump(2) << "\n";
    if (!out) {
      fs::remove(partial, ec);
      return;
    }
  }
  fs::rename(partial, file, ec);
}

}  // namespace bounce
