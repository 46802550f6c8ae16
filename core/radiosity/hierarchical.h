// Hierarchical radiosity with clustering (Hanrahan, Salzman & Aupperle
// 1991; Smits, Arvo & Greenberg 1994; Sillion 1995).
//
// Unknowns: one radiosity per element (piecewise constant), published to
// the vertices as the area-weighted mean of the elements around each one.
// Nodes of the cluster tree (cluster_tree.h) exchange light through links:
// a link (receiver <- source) carries a form-factor estimate and the
// visible fraction from shadow rays. A link is split, on its larger side,
// while the power it would carry, F x B_source x A_receiver, exceeds the
// tolerance (a fraction of the scene's emitted power); partly visible
// links must be four times smaller. Leaf-to-leaf links use Lambert's exact
// point-to-polygon term from the receiver's centroid.
//
// An operator application is Hanrahan's gather and push-pull: pull the
// element radiosities up the tree (area-weighted means), gather every link
// into its receiver (clusters gather by direction into six axis bins),
// push the gathered irradiance down to the elements and reflect it. The
// system B = E + K B is solved with BiCGSTAB on that operator (Eigen,
// matrix-free), so high reflectance does not stall it; between blocks of
// iterations the links are refined with the tolerance lowered, with the
// radiosity found so far as the oracle's B.
//
// Elements (lazy refinement below the input mesh): an element-to-element
// pair cannot be split in the tree. Where the light it carries matters and
// is partly shadowed or varies over the receiving element, that element
// is marked with the bisections that would bring the error under the
// tolerance (evenly lit elements never are). At the next link refinement
// the marked elements are first bisected (Rivara's conforming
// longest-edge bisection, no element edge below min_edge), each becoming
// a node of the tree over its pieces, the radiosity carried to the
// pieces; the links are then refined onto them. Elements are fine only
// where some link needs them: at contacts, shadow edges and gradients.
//
// Planar mirrors: links also join pairs through chains of planar mirrors
// (mirror_chains.h), refined by the same oracle on the source's image, so
// light that mirrors pass on between diffuse surfaces (D S+ D) is part of
// the operator. Curved mirrors and glass are carried by passes over the
// patches (params.specular_bounces) and the right-hand side.
//
// Closed scenes: every element's form factors must sum to 1; the estimates
// of coarse links do not quite, and at rho = 0.999 an error of 1e-4 in the
// sum is 10% in B. Where the scene is closed (no sampled ray escapes it),
// each element's gathered irradiance is divided by its form-factor sum.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/cluster_tree.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/hierarchical/mirror_chains.h"

namespace bounce {

struct hierarchical_params {
  // Final link tolerance, as a fraction of the scene's emitted power; the
  // first links are made at tolerance x refine_factor^rounds, and every
  // refinement divides it by refine_factor.
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
  // two per tree node more) and a warning says so: 512 MiB of links.
  std::size_t max_links = 32'000'000;
  bool normalize_closed = true;
  // Largest final gather (kernel evaluations) made at each publication.
  std::uint64_t gather_budget = 60'000'000;
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

// 16 bytes: what one link costs (plus the receiver index lists).
struct hierarchy_link {
  int receiver = -1;
  int source = -1;
  float factor = 0.0f;      // form factor (clusters: per unit area facing the source)
  float visibility = 1.0f;  // fraction of the shadow rays that pass
};

// A link through a chain of planar mirrors: the receiver sees the
// source's image (solver.chains[chain]); factor is the form factor to the
// image, visibility the share of rays that pass the chain.
struct mirror_link {
  hierarchy_link link;
  int chain = -1;
};

struct hierarchy_progress {
  double tolerance = 0.0;    // the oracle's current tolerance (fraction of emitted power)
  bool links_final = false;  // tolerance has reached its final value
  int refinements = 0;       // link refinement rounds made
  std::uint64_t steps = 0;   // steps made (publications)
  std::uint64_t operator_applications = 0;
  std::uint64_t jacobi_fallbacks = 0;   // steps where BiCGSTAB did not lower the residual
  double previous_residual = INFINITY;  // the residual fraction at the previous step
  std::uint64_t rays = 0;
  bool closed = false;  // the scene is closed: form factors normalised
  std::uint64_t gather_evaluations = 0;
  int element_passes = 0;                 // mesh refinements made
  int specular_passes = 0;                // passes of diffuse light through mirrors and glass made
  std::uint64_t specular_ray_budget = 0;  // rays a pass may cast (set by the first)
  double specular_shot_fraction = 1.0;    // share of the reflected power the last pass shot itself
  std::size_t split_marks = 0;            // elements marked for bisection, over all passes
  std::string warning;                    // e.g. the link limit was reached
};

struct hierarchical_solver {
  const patch_mesh* mesh = nullptr;                // the mesh solved: the input mesh, or refined_mesh
  const patch_mesh* input_mesh = nullptr;          // the mesher's (a restart returns to it)
  std::shared_ptr<const patch_mesh> refined_mesh;  // the input mesh with elements split, once any are
  const scene* source = nullptr;
  hierarchical_params params;
  form_factor_context context;  // occlusion, shadow-ray offset and the point lights' rays
  double min_edge = 0.0;        // resolved: elements are not split below it
  cluster_tree tree;
  std::vector<hierarchy_link> links;      // sorted by receiver
  std::vector<std::size_t> link_offsets;  // per receiver node: its links are [offsets[i], offsets[i+1])
  std::vector<int> cube_slot;             // per node: its six-bin slot, or -1 for oriented nodes
  std::vector<mirror_chain> chains;       // empty: no links through mirrors
  std::vector<mirror_link> mirror_links;  // sorted by receiver
  std::vector<std::size_t> mirror_link_offsets;
  bool has_path_targets = false;  // curved mirrors or glass: the passes have paths to trace
  // Per element, the bisections the last link refinement asked for (empty: none).
  std::vector<std::uint8_t> split_marks;
  // Per node, after elements were split: 1 for the leaves that became the
  // roots of their pieces. A link refinement at the same tolerance then
  // looks only at their links (empty: at every link).
  std::vector<std::uint8_t> split_roots;
  // Working arrays of an operator application, sized with the tree (one
  // caller at a time: the solver's own thread).
  struct transport_buffers {
    std::vector<rgb> node_b;
    std::vector<rgb> gathered;             // oriented nodes: irradiance gathered by their own links, then pushed
    std::vector<std::array<rgb, 6>> bins;  // clusters: irradiance per unit area facing +x, -x, ...
    std::vector<std::array<rgb, 6>> sent;  // clusters: what their elements send towards +x, -x, ... (pull)
    std::vector<rgb> mirrored;             // per element: irradiance through the mirror links
  };
  mutable transport_buffers buffers;

  // Per element
  std::vector<rgb> rho;
  std::vector<rgb> emission;  // E
  std::vector<rgb> lamp;      // radiosity reflected from point lights (part of the right-hand side)
  // The part of lamp that arrives from the emitters and point lights by
  // way of mirrors and glass (specular_light_from_sources: found once on
  // the input mesh, each piece of a split element keeping its element's);
  // not direct light. Empty when the specular transfer is off.
  // Once the final links are solved, it also holds the diffuse light that
  // they pass on (params.specular_bounces).
  std::vector<rgb> specular_lamp;
  std::vector<rgb> specular_lamp_input;
  std::vector<int> input_element;  // per element: the input mesh's element it lies in
  std::vector<double> normalizer;  // 1 / form-factor sum in closed scenes, else 1
  std::vector<rgb> radiosity;      // B (the solution)
  std::vector<rgb> direct;         // the part of B received straight from emitters and point lights
  std::vector<rgb> mirrored;       // the part received from emitters through mirror links (a caustic)
  std::vector<rgb> residual;       // E + lamp + K B - B
  // Final gather: each element's reflected light with the kernel evaluated
  // at the element itself over the links of it and its ancestors.
  std::vector<rgb> gathered, gathered_direct, gathered_mirrored;

  double emitted_power = 0.0;  // channel sum of the right-hand side x area
  double residual_fraction = 1.0;
  hierarchy_progress progress;
};

// Builds the tree, finds whether the scene is closed, and gives the point
// lights' direct light to every element. Links come with the first step.
std::unique_ptr<hierarchical_solver> make_hierarchical_solver(const scene& s, const patch_mesh& mesh,
                                                              const form_factor_context& context,
                                                              const hierarchical_params& params);

// Back to B = E with the first, coarsest links.
void restart_hierarchical(hierarchical_solver& solver);

// One step: the first makes the coarsest links and one Jacobi sweep (the
// direct light everywhere); the next run a block of BiCGSTAB iterations,
// and refine the links once the residual is below `refine_below` (a
// fraction of the emitted power) until the tolerance is final. Returns
// false when there is nothing left to improve.
bool step_hierarchical(hierarchical_solver& solver, double refine_below);

// Refines every link against the current solution at `tolerance` (or
// makes the first links from the root's self-link when there are none).
// With params.split_elements, marks the elements that element-to-element
// links need split (split_marks).
void refine_links(hierarchical_solver& solver, double tolerance);

// Whether the links are final and no element is still to be split: the
// solution's discretisation will not change any more.
bool refinement_done(const hierarchical_solver& solver);

// Whether the passes of diffuse light through mirrors and glass
// (params.specular_bounces) are all made, or none is due (nothing
// specular, or the transfer off): the right-hand side is then final too.
bool specular_passes_done(const hierarchical_solver& solver);

// Bisects the marked elements (conforming, not below min_edge), carries
// the radiosity over (each piece keeps its element's), extends the tree
// with subtrees over the pieces (extend_cluster_tree: the links stay,
// renumbered; the next refine_links splits them onto the pieces) and
// remakes the per-element data. Returns false if nothing was split (with
// a warning if the mesh would grow past the mesher's limit).
bool split_marked_elements(hierarchical_solver& solver);

// The operator: out = K x (x per element), K = reflect . push . gather . pull.
void apply_transport(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out);

// Final gather over the current solution (fills gathered,
// gathered_direct and gathered_mirrored, the emitters' light through
// mirror links): each element gathers over the links of itself and its
// ancestors with the kernel evaluated at its own centre and normal. Costs
// the sum over elements of those links; past params.gather_budget it is
// not made and returns false.
bool final_gather(hierarchical_solver& solver);
std::uint64_t final_gather_cost(const hierarchical_solver& solver);

// Vertex values: the area-weighted mean of the elements around each vertex.
std::vector<rgb> element_to_vertex(const patch_mesh& mesh, const std::vector<rgb>& per_element);

// Links per receiving element: every link whose receiver holds the element
// counts, spread by area (links per unit area, for tests and the panel).
std::vector<double> link_density(const hierarchical_solver& solver);

// The element-level solution (every element gathers from every element,
// the leaf-to-leaf form factor and visibility of the hierarchical solver,
// normalised the same way), solved densely: small scenes only.
std::vector<rgb> element_level_solution(const hierarchical_solver& solver);

}  // namespace bounce
