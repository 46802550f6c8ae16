// Form factors from receiving vertices to a shooting element, by two
// methods behind one interface so they can be compared on the same scene.
//
// F(v, e) is the fraction of the power leaving a differential area at
// vertex v (normal n_v) that reaches element e; by reciprocity it is also
// what v receives from e per unit of e's radiosity: dB_v = rho_v F(v, e) B_e.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

class occlusion_scene;
struct mirror_set;

// Lambert's contour formula: the exact unoccluded form factor from a
// differential area at p (unit normal n) to a planar polygon, after clipping
// the polygon to p's upper hemisphere. Returns >= 0.
double point_polygon_form_factor(const vec3& p, const vec3& n, std::span<const vec3> polygon);

enum class form_factor_method { raycast, hemicube };

struct form_factor_params {
  form_factor_method method = form_factor_method::raycast;
  // raycast (Wallace 1989): analytic polygon term x visible fraction from
  // stratified shadow rays to the shooter (rounded up to a square number)
  int shadow_rays = 16;
  // rays only where visibility is partial: a 2x2 probe first; the full
  // grid only when the probe's rays disagree (or the shooter is large)
  bool adaptive_rays = true;
  // a partly visible shooter is split in four while its size exceeds this
  // fraction of its distance to the receiver, to `max_subdivision` levels
  double subdivide_ratio = 1.0;
  int max_subdivision = 2;
  // hemicube (Cohen & Greenberg 1985): pixels along the top face's side
  int hemicube_resolution = 128;
  std::uint64_t seed = 1;  // jitter of the shadow rays; F(v, e) depends on (seed, v, e) only
  // Light by way of mirrors and glass, in scenes whose materials have kr or
  // kt: through planar mirrors by mirror images, to `mirror_depth`
  // reflections (mirror_images.h); through curved mirrors and glass by
  // `specular_paths` traced paths per shot, each followed through up to
  // `specular_bounces` specular events (specular_paths.h). Off: mirrors and
  // glass are their diffuse part alone (glass casts an opaque shadow).
  bool specular_transfer = true;
  int mirror_depth = 2;
  int specular_paths = 1024;
  int specular_bounces = 16;
  bool parallel = true;  // TBB over receivers (raycast) or hemicube faces
};

// What a method needs that lasts across shots: the Embree scene, each
// vertex's share of area (hemicube), offsets.
struct form_factor_context {
  const patch_mesh* mesh = nullptr;
  form_factor_params params;
  std::shared_ptr<const occlusion_scene> occlusion;
  std::vector<double> vertex_areas;  // a third of the incident elements' area
  double offset = 0.0;               // self-intersection offset, see make_form_factor_context
  // Planar mirrors (mirror_images.h), for shooters seen through them; set
  // by the solver (the mesher's mesh does not know the materials), may be null.
  std::shared_ptr<const mirror_set> mirrors;
};

form_factor_context make_form_factor_context(const patch_mesh& mesh, const form_factor_params& params);

// F(v, element) for every vertex v into out (size vertex_count()).
// Returns the number of shadow rays cast.
std::uint64_t form_factors_to_element(const form_factor_context& context, int element, std::span<double> out);

// F(v, patch) for every vertex v: the patch's outline triangle as one
// shooter (what the progressive solver shoots). Returns the rays cast.
std::uint64_t form_factors_to_patch(const form_factor_context& context, int patch, std::span<double> out);

// Planar mirrors a shooter is seen through (mirror_images.h): indices into
// the context's mirror set, the receiver's side first, and the product of
// their reflectances.
inline constexpr int max_mirror_depth = 4;
struct mirror_path {
  std::array<int, max_mirror_depth> mirrors{};
  int count = 0;
  rgb kr{1.0};
};

// A shooting triangle: an element, or a patch that elements tile; or the
// mirror image of one (Wallace, Cohen & Greenberg 1987), then seen only
// through its mirrors (`through`) and always by ray casting.
struct shooter {
  std::array<vec3, 3> corners;
  vec3 normal{0.0};
  double area = 0.0;
  int element = -1;     // the element itself, or -1 for a patch
  int patch = -1;       // the patch whose elements it covers, or -1 for an element
  mirror_path through;  // empty for a real shooter
  // Whether an element is part of the shooter (it does not see itself).
  bool contains(const patch_mesh& mesh, std::size_t e) const {
    return element >= 0 ? int(e) == element : mesh.element_patches[e] == patch;
  }
};

// The patch as a shooter.
shooter patch_shooter(const patch_mesh& mesh, int patch);

// How a receiver sees a shooter, from its shadow rays.
enum visibility_class : std::uint8_t { hidden, seen_partly, seen_whole, facing_away };

// Ray-cast F(v, from) (whatever the context's method) for the listed
// receivers, or every vertex when `receivers` is empty; out, and
// visibility when not empty, are indexed like the receivers. What adaptive
// refinement uses to gather at new vertices and to find shadow boundaries.
std::uint64_t form_factors_by_rays(const form_factor_context& context, const shooter& from,
                                   std::span<const int> receivers, std::span<double> out,
                                   std::span<std::uint8_t> visibility = {});

// Shadow-ray visibility of a segment, with both ends lifted off their
// surfaces along their normals by the context's offset.
bool visible(const form_factor_context& context, const vec3& from, const vec3& from_normal, const vec3& to,
             const vec3& to_normal);

}  // namespace bounce
