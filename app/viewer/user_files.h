// Files the window finds or keeps for its user: the scenes shipped with
// Bounce wherever it runs from, and the recently opened scenes, kept in the
// user's configuration folder ($XDG_CONFIG_HOME/bounce, else
// ~/.config/bounce).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "viewer/panel.h"

namespace bounce {

// The user's configuration folder for Bounce; empty when neither
// XDG_CONFIG_HOME nor HOME is set.
std::filesystem::path config_folder();

// The shipped scenes: assets/*/*.json in the first assets folder found next
// to the executable (`exe`; default: this process's), above it (a build
// folder inside the source tree), in ../share/bounce (installed), or in the
// current folder; then the built-in and generated scenes, which need no
// files.
std::vector<std::string> find_asset_scenes(const std::filesystem::path& exe = {});

// The recently opened scenes, most recent first (at most 10).
std::vector<std::string> read_recent_scenes();

// Puts `source` first in the recent list (files as absolute paths; the
// built-in default is not listed), saves the list, and returns it. A list
// that cannot be saved stays in memory: it is a convenience, not data.
std::vector<std::string> remember_scene(const std::string& source);

// Camera bookmarks, per scene, in bookmarks.json in the configuration
// folder. Entries that do not read back as cameras are skipped.
std::vector<camera_bookmark> read_bookmarks(const std::string& scene_source);
void save_bookmarks(const std::string& scene_source, const std::vector<camera_bookmark>& bookmarks);

// A file name in the current folder that no file has yet, for a picture
// the user asked for without naming it: "cornell_box-screenshot-
// 20261128-101530.png" (the scene's name, the kind, local time), then
// "-2", "-3"... when a file of that name exists.
std::string dated_file_name(const std::string& scene_source, const std::string& kind, const std::string& extension);

// The panel's layout (shown or hidden, its width), in panel.json in the
// configuration folder; the defaults when there is none or it does not
// read. Saved whole (written beside, then renamed over the old one).
panel_layout read_panel_layout();
void save_panel_layout(const panel_layout& layout);

}  // namespace bounce
