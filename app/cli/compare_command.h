// `bounce compare`: the error of one PFM picture against a reference PFM.
#pragma once

#include <string>

namespace bounce {

// `factor`: box-filter blocks of factor x factor pixels first; `bright` > 0:
// leave out pixels where the reference exceeds it (emitters).
int run_compare(const std::string& test_path, const std::string& reference_path, int factor, double bright);

}  // namespace bounce
