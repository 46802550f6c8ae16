// The hierarchical solver's knobs (solver.h describes the method). The
// command line sets the tolerance; the rest are defaults that the bench
// chose, and tests set to isolate one behaviour.
#pragma once

#include <cstddef>
#include <cstdint>

namespace bounce {

struct hierarchical_params {
  // Final link tolerance, as a fraction of the power leaving all surfaces;
  // the first links are made at tolerance x refine_factor^rounds, and
  // every refinement divides it by refine_factor.
  double tolerance = 1e-5;
  double refine_factor = 8.0;
  int rounds = 3;
  // Partly visible links must carry this many times less than the tolerance.
  double partial_factor = 4.0;
  int visibility_rays = 4;       // rays per link between clusters or inner nodes
  int leaf_visibility_rays = 4;  // rays per element-to-element link
  int iterations_per_step = 4;   // BiCGSTAB iterations between publications
  // Links are refined once the residual is below this fraction of the
  // emitted power: each tolerance solved as far as the oracle needs.
  double refine_below = 0.02;
  // Past it no link is split (the pairs under way become links, at most
  // two per tree node more) and a warning says so: 512 MB of links.
  std::size_t max_links = 32'000'000;
  bool normalize_closed = true;
  // Largest final gather (kernel evaluations) made at each publication.
  std::uint64_t gather_budget = 60'000'000;
  // The final gather's visibility of a partly visible link, cast from the
  // vertex itself: rays per link from an emitting source, and from any
  // other (0: the link's own visibility, the mean over its receiver).
  int gather_emitter_rays = 16;
  int gather_partial_rays = 2;
  // Element refinement: off unless asked for (tests of the fixed mesh).
  // min_edge 0 means the mesh's max_edge / 8.
  bool split_elements = false;
  double min_edge = 0.0;
  int max_bisections = 4;  // per element and refinement
  // Mesh refinements in all: one with each link refinement, then more at
  // the final tolerance.
  int max_element_passes = 6;
  // Fewer marked elements than this fraction of them do not pay for a
  // mesh refinement (a copy of the mesh, an extended tree).
  double min_marked_fraction = 1e-3;
  bool parallel = true;
  std::uint64_t seed = 1;
  // Links through chains of planar mirrors (up to the form-factor
  // params' mirror_depth). Off: the passes below carry that light too, by
  // mirror images of every patch.
  bool mirror_links = true;
  // Passes of diffuse light through mirrors and glass (D S+ D): once the
  // final links are solved, each patch's reflected light is sent through
  // them and added to the right-hand side; each pass starts from the
  // solution that the one before led to, so n passes carry light that
  // mirrors and glass pass on between diffuse surfaces n times.
  int specular_bounces = 2;
  // Each pass casts at most this many times the rays the solve cast before
  // the first (at least specular_min_rays): past it, the most powerful
  // patches stand in for the rest (specular_light_from_patches).
  double specular_ray_share = 1.0;
  std::uint64_t specular_min_rays = 8'000'000;
};

}  // namespace bounce
