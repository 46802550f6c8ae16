#include "cli/compare_command.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

#include <CLI/CLI.hpp>

#include "cli/option_values.h"
#include "common/exit_code.h"
#include "image/image.h"
#include "image/image_metrics.h"

namespace bounce {
namespace {

// The first pixel of `img` with a channel that is not finite, as "x,y", or
// an empty string.
std::string first_non_finite_pixel(const image& img) {
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    if (!std::isfinite(img.pixels[i])) {
      const std::size_t pixel = i / 3;
      return std::to_string(pixel % std::size_t(img.width)) + "," + std::to_string(pixel / std::size_t(img.width));
    }
  return {};
}

}  // namespace

void add_compare_options(CLI::App& command, compare_options& options) {
  command.add_option("TEST", options.test_path, "picture to measure (PFM)")->required();
  command.add_option("REFERENCE", options.reference_path, "reference picture (PFM), the same size")->required();
  command
      .add_option("--exclude-above", options.exclude_above,
                  "leave out pixels (and their neighbours) where the reference exceeds this radiance: emitters")
      ->check(number_in(0.0, INFINITY, true));
  command.add_option("--downsample", options.downsample, "box-filter N x N blocks of both first (N at most the size)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
}

int run_compare(const compare_options& options) {
  const std::string& test_path = options.test_path;
  const std::string& reference_path = options.reference_path;
  const int factor = options.downsample;
  const double bright = options.exclude_above;
  image test, reference;
  std::string error;
  if (!read_pfm(test_path, test, error) || !read_pfm(reference_path, reference, error)) {
    std::cerr << "error: " << error << "\n";
    return exit_input_error;
  }
  // A NaN would drop out of every measure (NaN marks excluded pixels) and
  // an infinity swamp them: refused, not measured.
  for (const auto& [path, img] : {std::pair{&test_path, &test}, std::pair{&reference_path, &reference}})
    if (std::string at = first_non_finite_pixel(*img); !at.empty()) {
      std::cerr << "error: " << *path << ": pixel (" << at
                << ") is not a finite number (NaN or infinity); the picture cannot be compared\n";
      return exit_input_error;
    }
  if (test.width != reference.width || test.height != reference.height) {
    std::cerr << "error: " << test_path << " is " << test.width << "x" << test.height << " but " << reference_path
              << " is " << reference.width << "x" << reference.height << "\n";
    return exit_input_error;
  }
  if (factor > test.width || factor > test.height) {
    std::cerr << "error: --downsample " << factor << " is larger than the pictures (" << test.width << "x"
              << test.height << ")\n";
    return exit_usage;
  }
  if (bright > 0.0) {
    const std::vector<bool> emitters = bright_pixels(reference, bright);
    exclude_pixels(test, emitters, 1);
    exclude_pixels(reference, emitters, 1);
  }
  test = downsample(test, factor);
  reference = downsample(reference, factor);
  if (mean_radiance(reference) <= 0.0 || std::isnan(relative_rmse(test, reference)) ||
      std::isinf(relative_rmse(test, reference))) {
    std::cerr << "error: " << reference_path
              << ": no pixel left to compare against, or all of them black (relative errors need a reference "
                 "brighter than zero)"
              << (bright > 0.0 ? "; try a larger --exclude-above" : "") << "\n";
    return exit_input_error;
  }
  std::printf("mean radiance: test %.6g, reference %.6g (ratio %.5f)\n", mean_radiance(test), mean_radiance(reference),
              mean_radiance(test) / mean_radiance(reference));
  std::printf("relative RMSE %.5f, mean relative error %.5f, max relative error %.4f (%dx%d after %dx downsampling)\n",
              relative_rmse(test, reference), mean_relative_error(test, reference), max_relative_error(test, reference),
              test.width, test.height, factor);
  return exit_ok;
}

}  // namespace bounce
