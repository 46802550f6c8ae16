// Light by way of planar mirrors, through mirror images (virtual
// shooters: Wallace, Cohen & Greenberg 1987; Sillion & Puech 1989).
//
// A receiver sees a shooter in a planar mirror as the shooter's image
// across the mirror's plane, through the mirror's outline: the form factor
// to the image (Lambert's formula on the reflected triangle), weighted by
// the mirror's reflectance kr, with visibility from rays that must cross
// the plane inside the mirror and whose two legs (receiver to mirror,
// mirror to the real shooter) are clear. Images of images give paths over
// two or more mirrors. A planar mirror is a flat-shaded plane of one
// surface whose material reflects (kr > 0) and does not transmit (kt = 0);
// it reflects on its front side (a two-sided material's back is a mirror
// of its own). Everything else specular is followed by specular_paths.h.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/patch_mesh.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {

class occlusion_scene;

struct planar_mirror {
  vec3 normal{0.0};  // unit, the reflecting side; the plane is dot(normal, x) = offset
  double offset = 0.0;
  rgb kr{0.0};
  int surface = -1;
  int material = -1;
  double area = 0.0;
  std::vector<vec3> corners;                       // its elements' vertices (for culling)
  std::shared_ptr<const occlusion_scene> outline;  // its elements alone: where a segment crosses it

  double side(const vec3& x) const { return glm::dot(normal, x) - offset; }
  vec3 reflect_point(const vec3& x) const { return x - 2.0 * side(x) * normal; }
  vec3 reflect_direction(const vec3& d) const { return d - 2.0 * glm::dot(normal, d) * normal; }
};

struct mirror_set {
  std::vector<planar_mirror> mirrors;
  std::vector<std::uint8_t> element_mirror;  // per element: 1 when it is part of a planar mirror
  double tolerance = 0.0;                    // distances to a plane below this count as on it
};

// Planar mirrors grow in number as the square of the depth's images per
// shot: a surface and material that would make more planes than this (a
// faceted curved mirror) is left to the specular paths, and so is any
// plane past max_planar_mirrors in all.
inline constexpr int max_planes_per_mirror_surface = 8;
inline constexpr int max_planar_mirrors = 16;

// The planar mirrors of the mesh (null when there are none).
std::shared_ptr<const mirror_set> find_planar_mirrors(const scene& s, const patch_mesh& mesh);

// The images of `from` in the mirrors, up to `depth` reflections: every
// chain of mirrors (no mirror twice in a row) in which each reflected
// shooter lies wholly in front of the next mirror and faces some of it.
// Each image carries its path (receiver's side first) and kr product.
std::vector<shooter> mirror_images(const mirror_set& mirrors, const shooter& from, int depth);

// The images of a punctual light the same way: the light reflected (its
// position and direction) with its path. A point or spot must lie in front
// of the mirror; a sun must shine on the mirror's front.
struct light_image {
  punctual_light light;
  mirror_path through;
};
std::vector<light_image> mirror_images(const mirror_set& mirrors, const punctual_light& light, int depth);

// The images of all the scene's punctual lights.
std::vector<light_image> light_images(const scene& s, const mirror_set& mirrors, int depth);

// Irradiance the images give a point p facing n: kr I cos / r^2 from each
// (kr E cos from a sun's), with shadow rays through the mirrors. Adds the
// rays cast to `rays`.
rgb mirrored_light_irradiance(const form_factor_context& context, const std::vector<light_image>& images, const vec3& p,
                              const vec3& n, std::uint64_t& rays);

// Whether light runs from `to`, a point on an image (lifted off it), to
// `from`, a receiving point (lifted off its surface), by way of the path's
// mirrors: the segment crosses each mirror's plane inside the mirror, and
// every leg between the mirror points is clear in the context's occlusion.
bool visible_through_mirrors(const form_factor_context& context, const mirror_path& path, const vec3& from,
                             const vec3& to);

// Radiosity each vertex (from `first` on) reflects of the punctual lights
// seen in the mirrors: rho kr I cos / r^2 from each image (rho kr E cos
// from a sun's). Adds the rays
// cast to `rays`.
std::vector<rgb> mirrored_point_light_radiosity(const scene& s, const patch_mesh& mesh,
                                                const form_factor_context& context, int depth, std::uint64_t& rays,
                                                std::size_t first = 0);

}  // namespace bounce
