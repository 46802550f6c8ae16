// Outputs written whole or not at all (base/whole_file.h): a failed write
// leaves the old file byte for byte and nothing beside it; a full disk is
// an error, not a short file; a symbolic link's file is replaced, not the
// link.
#include "base/whole_file.h"

#include <csignal>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "child_process.h"
#include "image/image.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::read_text;
using test_support::scratch_dir;

bool leftovers(const scratch_dir& dir) {
  for (const auto& entry : std::filesystem::directory_iterator(dir.root))
    if (entry.path().string().find(".partial") != std::string::npos) return true;
  return false;
}

TEST(WholeFile, AFailedWriteLeavesTheOldFileAndNothingBeside) {
  scratch_dir dir;
  const std::string path = dir.write("picture.png", "old picture");
  std::string error;
  EXPECT_FALSE(write_whole(
      path,
      [](const std::string& file, std::string& reason) {
        std::ofstream(file) << "half a pic";
        reason = "encoder gave up";
        return false;
      },
      error));
  EXPECT_EQ(error, path + ": encoder gave up");
  EXPECT_EQ(read_text(path), "old picture");
  EXPECT_FALSE(leftovers(dir));
  // And a good write replaces it whole.
  EXPECT_TRUE(write_whole(
      path, [](const std::string& file, std::string& reason) { return write_bytes(file, "new picture", reason); },
      error));
  EXPECT_EQ(read_text(path), "new picture");
  EXPECT_FALSE(leftovers(dir));
}

// A disk that fills up mid-write (here a file size limit, in a child
// process): the writer reports the system's reason and the old file stays.
TEST(WholeFile, AFullDiskIsAnErrorWithItsReason) {
  scratch_dir dir;
  const std::string path = dir.write("big.png", "old picture");
  EXPECT_TRUE(test_support::holds_under_limit(RLIMIT_FSIZE, 4096, [&] {
    std::signal(SIGXFSZ, SIG_IGN);  // writes past the limit fail with EFBIG instead
    std::vector<unsigned char> noise(512 * 512 * 3);
    for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<unsigned char>(i * 2654435761u >> 24);
    std::string error;
    const bool written = write_png(path, 512, 512, 3, noise.data(), error);
    return !written && error.find("File too large") != std::string::npos;
  })) << "write_png did not report the full file";
  EXPECT_EQ(read_text(path), "old picture");
  EXPECT_FALSE(leftovers(dir));
}

TEST(WholeFile, ASymbolicLinksFileIsReplacedNotTheLink) {
  scratch_dir dir;
  const std::string real = dir.write("real.json", "old");
  const std::string link = dir.path("link.json");
  std::filesystem::create_symlink(real, link);
  std::string error;
  ASSERT_TRUE(write_whole(
      link, [](const std::string& file, std::string& reason) { return write_bytes(file, "new", reason); }, error))
      << error;
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_EQ(read_text(real), "new");
}

}  // namespace
}  // namespace bounce
