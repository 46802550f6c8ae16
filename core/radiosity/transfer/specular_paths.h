// Light through curved mirrors and glass, by tracing (the part of the
// specular transfer that mirror images cannot do: mirror_images.h).
//
// A source (a shooting triangle, or a punctual light) sends paths toward the
// specular elements that are not planar mirrors: element j is chosen in
// proportion to an estimate of the power it receives from the source (its
// area times the form factor from its centre, with a floor so that every
// element the source can reach keeps a chance), a point y uniformly on
// it, a point x uniformly on the source, and the path carries
//   B cos_x cos_y / (pi r^2) A_source A_j / (p_j N)   (triangle, radiosity B)
//   E cos_y A_j / (p_j N)          (punctual light: E its irradiance at y)
// when the segment x -> y first meets element j: an unbiased estimate of
// the power the specular elements receive. From there it is followed
// through reflection and refraction (specular_event.h: Fresnel where the
// material asks for it, total internal reflection) by Russian roulette on
// the mean of the weights, as the caustic photons are. Where it meets the
// front of a surface with diffuse reflectance it deposits its power there,
// on the vertices of the element met in proportion to the barycentric
// coordinates, as irradiance (power over the vertex's share of area), and
// goes on with that surface's specular part if any. Paths that reach a
// diffuse surface directly, or by planar mirrors, are not traced: form
// factors and mirror images carry them.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

struct mirror_set;

// The elements paths are sent toward: specular (kr or kt > 0) and not part
// of a planar mirror. Null when there are none. Chains that begin at a
// planar mirror and go on to one of those (a lamp seen in a wall mirror by
// a mirror ball) are neither the mirror images' (planar mirrors alone) nor
// the direct paths': paths are also sent toward the planar mirrors'
// elements, and deposit only after their first event off a planar mirror.
struct specular_surfaces {
  std::vector<int> elements;
  std::vector<int> planar_mirror_elements;  // empty without planar mirrors
};
std::shared_ptr<const specular_surfaces> find_specular_surfaces(const scene& s, const patch_mesh& mesh,
                                                                const mirror_set* mirrors);

// Whether any material of the scene is specular (kr or kt > 0).
bool has_specular_materials(const scene& s);

// Where the power sent into specular paths went, per channel. Every path
// ends once: sent + reweighted = stopped + escaped + truncated + imaged, where a
// path's deposits on diffuse surfaces (deposited) do not end it.
struct specular_tally {
  rgb sent{0.0};       // arriving at the specular elements from the sources
  rgb deposited{0.0};  // arriving at diffuse surfaces after one or more specular events
  rgb stopped{0.0};    // not reflected or transmitted specularly any further (roulette)
  rgb escaped{0.0};    // left the scene
  rgb truncated{0.0};  // still going after the maximum of specular events
  rgb imaged{0.0};     // sent to a planar mirror, reached a diffuse surface by planar mirrors alone (the images' light)
  rgb reweighted{0.0};  // gained or lost by roulette on coloured weights (zero for grey ones)
  std::uint64_t paths = 0;
};
void add(specular_tally& to, const specular_tally& from);

// A source of specular paths: a shooter with its radiosity, or a punctual
// light.
struct specular_source {
  const shooter* from = nullptr;
  rgb radiosity{0.0};
  const punctual_light* light = nullptr;
};

// Traces `context.params.specular_paths` paths from the source toward the
// surfaces' elements, and half as many toward their planar mirrors' (if
// any), and adds the irradiance they deposit to `irradiance` (per vertex of the
// context's mesh). `seed` makes the paths (different shots: different
// seeds); the result does not depend on the threads. Returns the rays cast.
std::uint64_t trace_specular_paths(const scene& s, const form_factor_context& context,
                                   const specular_surfaces& surfaces, const specular_source& source, std::uint64_t seed,
                                   std::vector<rgb>& irradiance, specular_tally& tally);

// The light that reaches each vertex from the emitting patches and the
// point lights by way of mirrors and glass alone (one specular chain, then
// the vertex): mirror images of the emitting patches and of the point
// lights, and the specular paths of both, as reflected radiosity per
// vertex. What the hierarchical solver adds to its right-hand side (its
// links carry no light through mirrors). `surfaces` may be null (no
// paths); the context's mirrors may be null (no images). Without
// `patch_images`, the emitting patches' mirror images are left out (the
// hierarchical solver's links through mirrors carry them); without
// `light_images`, the punctual lights' (the hierarchical solver gathers
// them at its elements and vertices). Adds the rays cast to `rays`.
std::vector<rgb> specular_light_from_sources(const scene& s, const form_factor_context& context,
                                             const specular_surfaces* surfaces, std::uint64_t& rays,
                                             bool patch_images = true, bool light_images = true);

// The same from patches of the context's mesh, each radiating uniformly
// with `radiosity[patch]` (zero: skipped), without the point lights: what
// the hierarchical solver adds for diffuse light passed on by mirrors and
// glass (D S+ D). `seed` is advanced once per patch that traces paths.
// With a `ray_budget`, the patches go most powerful first and stop once
// the budget is spent; those shot then stand in for the rest (their light
// scaled by all the patches' power over theirs, which `shot_fraction`
// gets when given). Without `images`, the paths alone.
std::vector<rgb> specular_light_from_patches(const scene& s, const form_factor_context& context,
                                             const specular_surfaces* surfaces, const std::vector<rgb>& radiosity,
                                             std::uint64_t& seed, std::uint64_t& rays, std::uint64_t ray_budget = 0,
                                             double* shot_fraction = nullptr, bool images = true);

}  // namespace bounce
