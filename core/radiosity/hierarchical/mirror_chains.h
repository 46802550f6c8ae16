// Chains of planar mirrors that the hierarchical solver's links look
// through (docs/hierarchical.md, "Links through mirrors").
//
// A receiver sees a source by way of the mirrors m0, m1, ... (the
// receiver's side first) at the source's image: reflected in the last
// mirror, then in the one before, and so on to m0. A chain's image is an
// isometry, x -> linear x + shift, so a link through a chain is a link to
// the moved source: its form factor is the one to the image, its
// visibility comes from rays that must cross each mirror inside its
// outline (visible_through_mirrors), and what it carries is kr (the
// product over the chain) times the radiosity the source sends towards
// the mirror.
#pragma once

#include <vector>

#include <glm/mat3x3.hpp>

#include "radiosity/transfer/mirror_images.h"

namespace bounce {

struct mirror_chain {
  mirror_path path;        // receiver's side first; kr is the product
  glm::dmat3 linear{1.0};  // image of x: linear x + shift (orthogonal)
  vec3 shift{0.0};
  // The first mirror's outline in its plane: axes u, v and their extents.
  vec3 u{0.0}, v{0.0};
  double u_lo = 0.0, u_hi = 0.0, v_lo = 0.0, v_hi = 0.0;

  vec3 image(const vec3& x) const { return linear * x + shift; }
  vec3 image_direction(const vec3& d) const { return linear * d; }
  // A direction at the image, back in the source's frame.
  vec3 source_direction(const vec3& d) const { return glm::transpose(linear) * d; }
};

// Every chain of up to `depth` mirrors of the set, no mirror twice in a
// row, nor two mirrors of one plane in a row.
std::vector<mirror_chain> mirror_chains(const mirror_set& mirrors, int depth);

// The bounding box of the image of box [lo, hi].
void image_box(const mirror_chain& chain, const vec3& lo, const vec3& hi, vec3& image_lo, vec3& image_hi);

// Whether some point of box [lo, hi] lies more than `slack` in front of
// the mirror's plane (a source there may send light into the mirror).
bool box_reaches_in_front(const planar_mirror& mirror, const vec3& lo, const vec3& hi, double slack);

// Whether some segment from a point of box [lo, hi] (the receiver's side)
// to a point of box [image_lo, image_hi] (an image) may cross the chain's
// first mirror plane inside its outline, from its front: false means no
// light passes between the two that way. Conservative: the crossings are
// bounded from the boxes' extents along the mirror's axes and normal.
bool may_cross_first_mirror(const mirror_set& mirrors, const mirror_chain& chain, const vec3& lo, const vec3& hi,
                            const vec3& image_lo, const vec3& image_hi);

}  // namespace bounce
