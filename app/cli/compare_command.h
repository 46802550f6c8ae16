// `bounce compare`: the error of one PFM picture against a reference PFM.
#pragma once

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct compare_options {
  std::string test_path, reference_path;
  int downsample = 1;          // box-filter blocks of downsample x downsample pixels first
  double exclude_above = 0.0;  // > 0: leave out pixels where the reference exceeds it (emitters)
};

void add_compare_options(CLI::App& command, compare_options& options);
int run_compare(const compare_options& options);

}  // namespace bounce
