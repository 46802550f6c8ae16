// Scratch files for tests: each test gets its own folder under the build
// tree (test-scratch/), removed when the test ends, so that two build trees
// never share one and nothing is written beside the sources.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

namespace bounce::test_support {

struct scratch_dir {
  std::filesystem::path root;

  // `tag` tells apart several scratch folders of one test.
  explicit scratch_dir(const std::string& tag = "") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root = std::filesystem::path(BOUNCE_BINARY_DIR) / "test-scratch" /
           (std::string(info->test_suite_name()) + "." + info->name() + tag);
    std::filesystem::remove_all(root);
    std::filesystem::create_directories(root);
  }
  ~scratch_dir() {
    std::error_code ec;
    std::filesystem::remove_all(root, ec);
  }

  // Writes `contents` to root/name and returns the full path.
  std::string write(const std::string& name, const std::string& contents) const {
    std::filesystem::path p = root / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << contents;
    return p.string();
  }
  std::string path(const std::string& name) const { return (root / name).string(); }
};

// A whole file's text ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline std::string source_path(const std::string& relative) {
  return std::string(BOUNCE_SOURCE_DIR) + "/" + relative;
}

}  // namespace bounce::test_support
