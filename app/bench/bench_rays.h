// `bounce bench --suite rays`: the ray core's speed against Embree's own
// on the same rays (measure/ray_throughput.h), on the Whitted scene, the
// Cornell box and a generated interior of 100k triangles, at 512 x 512.
// Writes rays.json and rays.md into the output folder.
#pragma once

#include "bench/bench_command.h"

namespace bounce {

int run_ray_bench(const bench_options& options);

}  // namespace bounce
