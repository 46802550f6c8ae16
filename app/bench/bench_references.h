// The bench's path-traced reference pictures: where they are cached under
// the output folder, and tracing the ones a suite needs that are missing.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "bench/bench_suites.h"
#include "image/image.h"

namespace bounce {

// The cached reference of `scene` at size x size pixels and `spp` samples.
std::filesystem::path reference_path(const std::string& out_dir, const std::string& scene, int size, int spp);

// Writes a reference into the cache: aside, then renamed, so that an
// interrupted run leaves no truncated file. Prints the error and returns
// false on failure.
bool cache_reference(const std::filesystem::path& path, const image& reference);

// The reference pictures the suite needs, from the cache under out_dir or
// path traced now (and cached); one note per scene appended to `notes`.
// Prints the error and returns false on failure.
bool prepare_references(const suite_plan& plan, const std::string& out_dir, nlohmann::json& notes);

}  // namespace bounce
