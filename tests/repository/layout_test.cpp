// The source tree keeps its own rules: include arrows between the folders
// of core/ and of app/ point down their layers, and docs/architecture.md's
// source map names every core/ file. Read from the checkout
// (BOUNCE_SOURCE_DIR).
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_files.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;
using test_support::read_text;

// core/'s folders from the bottom up; a file may include its own folder's
// headers and those of folders on lower layers, never a sibling's on the
// same layer. docs/architecture.md gives the reasons.
const std::map<std::string, int> core_layers = {
    {"base", 0},
    {"image", 1},
    {"scene", 2},
    {"mesh", 3},
    {"optics", 3},
    {"radiosity/transfer", 4},
    {"radiosity/progressive", 5},
    {"radiosity/hierarchical", 5},
    {"radiosity", 6},
    {"trace", 6},
    {"measure", 7},
};

// app/'s folders from the bottom up, over all of core/ ("" is app/ itself:
// main.cpp).
const std::map<std::string, int> app_layers = {
    {"common", 0}, {"render", 1}, {"headless", 2}, {"viewer", 3}, {"bench", 3}, {"cli", 4}, {"", 5},
};

std::vector<fs::path> source_files(const std::string& root) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(BOUNCE_SOURCE_DIR) / root)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".h" || ext == ".cpp")) out.push_back(entry.path());
  }
  return out;
}

std::vector<fs::path> core_files() {
  return source_files("core");
}

// "radiosity/hierarchical" for core/radiosity/hierarchical/oracle.h.
std::string folder_of(const fs::path& file, const std::string& root = "core") {
  const std::string folder = fs::relative(file.parent_path(), fs::path(BOUNCE_SOURCE_DIR) / root).generic_string();
  return folder == "." ? "" : folder;
}

// Includes of `root`'s files that go up or sideways in `layers`.
std::vector<std::string> arrows_against(const std::string& root, const std::map<std::string, int>& layers) {
  const std::regex include(R"re(#include "([a-z_/]+)/([a-z_]+\.h)")re");
  std::vector<std::string> wrong;
  for (const fs::path& file : source_files(root)) {
    const std::string from = folder_of(file, root);
    if (!layers.count(from)) continue;
    const std::string text = read_text(file);
    for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it) {
      const std::string to = (*it)[1];
      if (to == from || !layers.count(to) || !fs::exists(fs::path(BOUNCE_SOURCE_DIR) / root / to)) continue;
      if (layers.at(to) >= layers.at(from))
        wrong.push_back(fs::relative(file, BOUNCE_SOURCE_DIR).generic_string() + " -> " + to + "/" +
                        std::string((*it)[2]));
    }
  }
  return wrong;
}

std::string listed(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& item : items) list += "\n  " + item;
  return list;
}

TEST(Layout, EveryCoreFolderHasALayer) {
  for (const fs::path& file : core_files())
    EXPECT_TRUE(core_layers.count(folder_of(file))) << file << ": its folder is missing from core_layers";
}

TEST(Layout, IncludeArrowsBetweenCoreFoldersPointDown) {
  const std::vector<std::string> wrong = arrows_against("core", core_layers);
  EXPECT_TRUE(wrong.empty()) << wrong.size() << " include arrows point up or sideways:" << listed(wrong);
}

TEST(Layout, IncludeArrowsBetweenAppFoldersPointDown) {
  for (const fs::path& file : source_files("app"))
    EXPECT_TRUE(app_layers.count(folder_of(file, "app"))) << file << ": its folder is missing from app_layers";
  const std::vector<std::string> wrong = arrows_against("app", app_layers);
  EXPECT_TRUE(wrong.empty()) << wrong.size() << " include arrows point up or sideways:" << listed(wrong);
}

TEST(Layout, CoreIncludesNothingOfApp) {
  for (const fs::path& file : core_files()) {
    const std::string text = read_text(file);
    for (const auto& [folder, layer] : app_layers) {
      if (folder.empty()) continue;
      EXPECT_EQ(text.find("#include \"" + folder + "/"), std::string::npos) << file << " includes app/" << folder;
    }
  }
}

TEST(Layout, TheArchitectureSourceMapNamesEveryCoreFile) {
  const std::string map = read_text(fs::path(BOUNCE_SOURCE_DIR) / "docs" / "architecture.md");
  ASSERT_FALSE(map.empty());
  std::set<std::string> missing;
  for (const fs::path& file : core_files()) {
    const std::string stem = file.stem().string();
    if (!std::regex_search(map, std::regex("\\b" + stem + "\\b"))) missing.insert(folder_of(file) + "/" + stem);
  }
  std::string list;
  for (const std::string& name : missing) list += "\n  " + name;
  EXPECT_TRUE(missing.empty()) << "docs/architecture.md does not name:" << list;
}

TEST(Layout, HeadersAndSourcesMatch) {
  // Every source file in core/ has its header (one concept per file).
  for (const fs::path& file : core_files()) {
    if (file.extension() != ".cpp") continue;
    fs::path header = file;
    header.replace_extension(".h");
    EXPECT_TRUE(fs::exists(header)) << file << " has no header of its own";
  }
}

}  // namespace
}  // namespace bounce
