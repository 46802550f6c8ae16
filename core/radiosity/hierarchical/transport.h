// The operator K of the system B = E + K B: Hanrahan's gather and
// push-pull over the links. An application pulls the element radiosities
// up the tree (area-weighted means; clusters also keep what their elements
// send towards each of six axis directions), gathers every link into its
// receiver (clusters gather by direction into six axis bins), pushes the
// gathered irradiance down to the elements, and reflects it (rho, and the
// closed-scene normaliser).
#pragma once

#include <array>
#include <vector>

#include "radiosity/hierarchical/state.h"

namespace bounce {

// Pull: per-element values x up the tree into node_b, as area-weighted
// means, level by level; with `sent`, also what each cluster's elements
// send towards +x, -x, +y, -y, +z, -z (sum of B x area x max(0, +-n_k)).
void pull(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& node_b,
          std::vector<std::array<rgb, 6>>* sent);

// The radiosity node `source` sends towards unit direction d: an oriented
// node's mean, or a cluster's directional estimate from `sent` (a mean
// over all its elements would count the sides that do not face d).
// `area` is the source's projected area along d (projected_area).
rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d, double area);
rgb sent_radiosity(const hierarchical_solver& solver, const std::vector<rgb>& node_b,
                   const std::vector<std::array<rgb, 6>>& sent, int source, const vec3& d);

// Gather and push over the links: out[e] = irradiance on element e from
// the plain links, and, when `mirrored` is given, mirrored[e] from the
// links through mirrors, and when `emitted` is given, emitted[e] from the
// emitter links alone (part of out; zeros when there are none). None is
// reflected nor normalised.
void gather_push(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out,
                 std::vector<rgb>* mirrored = nullptr, std::vector<rgb>* emitted = nullptr);

// The plain irradiance normalised (closed_scene.h): `emitted` is the part
// of `plain` through the emitter links.
inline rgb normalised(const rgb& plain, const rgb& emitted, const closed_scale& scale) {
  return (plain - emitted) * scale.rest + emitted * scale.emitters;
}

// out = K x (x per element): rho x (normalised plain irradiance + mirror
// irradiance). The normaliser applies to the plain links alone: a
// mirror's solid angle is counted once, by the plain links to it.
void apply_transport(const hierarchical_solver& solver, const std::vector<rgb>& x, std::vector<rgb>& out);

}  // namespace bounce
