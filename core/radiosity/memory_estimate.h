// The memory a radiosity solve takes, estimated from the scene before the
// mesher allocates anything, so that a scene too large for the machine is
// refused with figures (start_solve), and `bounce info` can say what a
// solve will need.
//
// Measured on this project (docs/performance.md): a solve's peak is about
// 2 kB per element at its start (the mesh and its half-edge build, the
// cluster tree, the per-element arrays, the occlusion BVH): 2.04 GB for
// 1.03M elements, 172 MB for 12k. The hierarchical solver's links add 16
// bytes each, up to its link limit, and splitting elements adds elements.
// The estimate is the start's: less than a solve's peak, so what it refuses
// could not have run.
#pragma once

#include <string>

#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace bounce {

inline constexpr double solve_bytes_per_element = 2000.0;
inline constexpr double solve_base_bytes = 64e6;  // the program, its libraries and the scene

struct solve_memory {
  double max_edge = 0.0;    // as the mesher will use it
  double elements = 0.0;    // the mesher's estimate (estimate_patch_elements)
  double bytes = 0.0;       // at the solve's start: base + elements x bytes per element
  double link_bytes = 0.0;  // hierarchical: the links at their limit (0: progressive)
};

solve_memory estimate_solve_memory(const scene& s, const solver_settings& settings);

// "about 1.03 million elements at max edge 4.03, 2 kB each": what the
// estimate counts, in words.
std::string describe(const solve_memory& need);

}  // namespace bounce
