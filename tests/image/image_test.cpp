// Image files: PFM and PNG round trips and their errors.
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "image/image.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::scratch_dir;

TEST(ImageFiles, PfmRoundTripIsExact) {
  scratch_dir dir;
  image img;
  img.width = 3;
  img.height = 2;
  for (int i = 0; i < 18; ++i) img.pixels.push_back(float(i) * 0.37f - 1.0f);
  std::string error;
  ASSERT_TRUE(write_pfm(dir.path("a.pfm"), img, error)) << error;
  image back;
  ASSERT_TRUE(read_pfm(dir.path("a.pfm"), back, error)) << error;
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.pixels, img.pixels);
  EXPECT_EQ(back.at(2, 1), rgb(img.pixels[15], img.pixels[16], img.pixels[17]));
  // Bottom-up storage: the first stored row is the image's last.
  std::ifstream raw(dir.path("a.pfm"), std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(raw)), {});
  float first;
  std::memcpy(&first, header.data() + header.find("-1.0\n") + 5, sizeof first);
  EXPECT_EQ(first, img.pixels[9]);
}

TEST(ImageFiles, PngRoundTripAndErrors) {
  scratch_dir dir;
  const unsigned char pixels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
  std::string error;
  ASSERT_TRUE(write_png(dir.path("a.png"), 2, 2, 3, pixels, error)) << error;
  int w = 0, h = 0;
  std::vector<unsigned char> back;
  ASSERT_TRUE(read_png_rgb8(dir.path("a.png"), w, h, back, error)) << error;
  EXPECT_EQ(w, 2);
  EXPECT_EQ(h, 2);
  EXPECT_EQ(back, std::vector<unsigned char>(pixels, pixels + 12));
  EXPECT_FALSE(write_png("/nonexistent/dir/a.png", 2, 2, 3, pixels, error));
  EXPECT_NE(error.find("/nonexistent/dir/a.png"), std::string::npos);
  image img;
  EXPECT_FALSE(read_pfm(dir.path("a.png"), img, error));
  EXPECT_NE(error.find("not a little-endian colour PFM"), std::string::npos);
}

}  // namespace
}  // namespace bounce
