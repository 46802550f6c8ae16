// Image files: PFM, PNG and OpenEXR round trips and their errors.
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <tinyexr.h>

#include "image/image.h"
#include "image/picture_file.h"
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

// OpenEXR is stored as half floats (11 bits of mantissa): read back with
// tinyexr's reader, every channel within 2^-11 relative; a picture large
// enough to be compressed (ZIP), as pictures are.
TEST(ImageFiles, ExrRoundTripKeepsHalfPrecision) {
  scratch_dir dir;
  image img;
  img.width = 37;
  img.height = 21;
  for (int i = 0; i < 3 * 37 * 21; ++i) img.pixels.push_back(float(0.001 + 0.37 * (i % 101) + (i % 3)));
  std::string error;
  ASSERT_TRUE(write_exr(dir.path("a.exr"), img, error)) << error;
  float* rgba = nullptr;
  int width = 0, height = 0;
  const char* message = nullptr;
  ASSERT_EQ(LoadEXR(&rgba, &width, &height, dir.path("a.exr").c_str(), &message), TINYEXR_SUCCESS)
      << (message ? message : "");
  ASSERT_EQ(width, 37);
  ASSERT_EQ(height, 21);
  for (std::size_t p = 0; p < std::size_t(width * height); ++p)
    for (std::size_t c = 0; c < 3; ++c)
      ASSERT_NEAR(rgba[4 * p + c], img.pixels[3 * p + c], img.pixels[3 * p + c] / 2048.0) << p << " " << c;
  std::free(rgba);
  EXPECT_FALSE(write_exr("/nonexistent/dir/a.exr", img, error));
  EXPECT_NE(error.find("/nonexistent/dir/a.exr"), std::string::npos) << error;
}

}  // namespace
}  // namespace bounce
