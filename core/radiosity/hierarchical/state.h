// The hierarchical solver's state (solver.h says how it evolves), in named
// parts: the meshes it solves, the tree and its links (the operator), the
// light sources per element (the right-hand side), the element light it
// has found, the marks on elements to split, the operator's working arrays
// and its progress.
//
// Invariants between steps: every per-element array is sized to
// meshes.current's elements; cube_slot, the link tables' offsets and the
// buffers are sized to tree's nodes; light.total, light.direct and
// light.mirrored hold the same elements.
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/cluster_tree.h"
#include "radiosity/hierarchical/link_table.h"
#include "radiosity/hierarchical/mirror_chains.h"
#include "radiosity/hierarchical/params.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/transfer/mirror_images.h"

namespace bounce {

// The mesh solved and the mesher's, which it refines.
struct solved_meshes {
  const patch_mesh* current = nullptr;        // the input mesh, or refined
  const patch_mesh* input = nullptr;          // the mesher's (a restart returns to it)
  std::shared_ptr<const patch_mesh> refined;  // the input mesh with elements split, once any are
  std::vector<int> input_element;             // per element: the input mesh's element it lies in
  double min_edge = 0.0;                      // resolved: elements are not split below it
  // Elements a view sees large may go below min_edge (element_refinement.h),
  // unless it was given (params.min_edge).
  bool min_edge_follows_view = true;
};

// What an element's gathered irradiance is scaled by in a closed scene, so
// that its form factors sum to 1: the links from emitting sources, and the
// others (closed_scene.h).
struct closed_scale {
  double rest = 1.0;
  double emitters = 1.0;
};

// The tree and the links over it: with rho and the normaliser, the
// operator K (transport.h).
struct link_hierarchy {
  cluster_tree tree;
  std::vector<int> cube_slot;  // per node: its six-bin slot, or -1 for oriented nodes
  link_table<hierarchy_link> links;
  std::vector<mirror_chain> chains;  // empty: no links through mirrors
  link_table<mirror_link> mirror_links;
  std::vector<rgb> rho;  // per element
  // Closed scenes: the plain links whose source emits, taken at face
  // value (their light is the direct light, found with care); the
  // normaliser makes up the form-factor sum's shortfall on the other
  // links. Empty in open scenes.
  link_table<hierarchy_link> emitter_links;
  std::vector<closed_scale> normalizer;  // per element (closed_scene.h); 1 and 1 in open scenes
};

// The right-hand side E + lamp, per element.
struct element_sources {
  std::vector<rgb> emission;  // E
  std::vector<rgb> lamp;      // radiosity reflected from point lights, and by way of mirrors and glass
  // The part of lamp that arrives from the emitters and point lights by
  // way of mirrors and glass (specular_light_from_sources: found once on
  // the input mesh, each piece of a split element keeping its element's);
  // not direct light. Empty when the specular transfer is off. Once the
  // final links are solved, it also holds the diffuse light that they pass
  // on (params.specular_bounces). specular_lamp_input is the emitters'
  // part per element of the input mesh.
  std::vector<rgb> specular_lamp;
  std::vector<rgb> specular_lamp_input;
  // The punctual lights seen in planar mirrors: their images, and the part
  // of lamp they give, found at each element like the lights' direct light
  // (and at the vertices by the final gather). Empty without mirrors.
  std::vector<light_image> light_images;
  std::vector<rgb> mirrored_lamp;
  double emitted_power = 0.0;     // channel sum of the right-hand side x area
  bool has_path_targets = false;  // curved mirrors or glass: the passes have paths to trace
};

// Light per element (the solution) or per vertex (the final gather): all
// of it, the part received straight from emitters and point lights, and
// the part received from emitters through mirror links (a caustic).
struct light_parts {
  std::vector<rgb> total;
  std::vector<rgb> direct;
  std::vector<rgb> mirrored;
};

// Working arrays of an operator application, sized with the tree (one
// caller at a time: the solver's own thread).
struct transport_buffers {
  std::vector<rgb> node_b;
  std::vector<rgb> gathered;             // oriented nodes: irradiance gathered by their own links, then pushed
  std::vector<std::array<rgb, 6>> bins;  // clusters: irradiance per unit area facing +x, -x, ...
  std::vector<std::array<rgb, 6>> sent;  // clusters: what their elements send towards +x, -x, ... (pull)
  std::vector<rgb> mirrored;             // per element: irradiance through the mirror links
  std::vector<rgb> emitted;              // per element: irradiance through the emitter links (closed scenes)
};

// The view that leads refinement (view_importance.h).
struct view_weights {
  std::vector<double> seen;     // per input element: the camera's rays per unit area (empty: no view)
  double rays_per_pixel = 0.0;  // along a side of the camera's picture: its size against the rays
  std::vector<double> node;     // per tree node: the receiver's weight (empty: every receiver weighs 1)
  bool retarget = false;        // a new view waits for the links to be refined for it
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
  // The last link refinement was cut short by the deadline: its links are
  // coarser than the tolerance asks where it had not yet reached.
  bool links_cut_short = false;
};

struct hierarchical_solver {
  const scene* source = nullptr;
  hierarchical_params params;
  form_factor_context context;  // occlusion, shadow-ray offset and the point lights' rays
  solved_meshes meshes;
  link_hierarchy hierarchy;
  element_sources sources;
  light_parts light;               // B, the solution
  std::vector<rgb> residual;       // E + lamp + K B - B
  double residual_fraction = 1.0;  // its power over the emitted power
  // Final gather: each vertex's reflected light with the kernel evaluated
  // at the vertex over the links above its elements (final_gather.h;
  // empty until made). Indexed by vertex, unlike `light`.
  light_parts gathered;
  // The vertices it gathered at: with a view, those of the elements the
  // view sees; empty: every vertex.
  std::vector<bool> gathered_at;
  view_weights view;
  // Per element, the bisections the last link refinement asked for
  // (empty: none; element_refinement.h).
  std::vector<std::uint8_t> split_marks;
  mutable transport_buffers buffers;
  hierarchy_progress progress;
  // The run's time limit: past it, link refinement splits no more pairs
  // (the rest stay links as they are) and the step ends.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();

  const patch_mesh& mesh() const { return *meshes.current; }
};

}  // namespace bounce
