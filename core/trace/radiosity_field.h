// The radiosity solution as a function on the scene's surfaces, for the ray
// tracer's second pass: the value at a point is interpolated from the
// vertices of the element of the same surface under it (a short probe ray
// along the normal), or else of the nearest one (an Embree closest-point
// query), so exact spheres and quadrics, and surfaces traced through a
// different tessellation, find their elements too.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "mesh/patch_mesh.h"

namespace bounce {

struct diffuse_radiosity {
  rgb reflected{0.0};  // B - E: the light the surface reflects (radiosity units)
  rgb indirect{0.0};   // the part of it that did not come straight from an emitter or point light
  rgb caustic{0.0};    // the part of it from the lights by way of mirrors and glass (0 if not kept apart)
};

class radiosity_field {
 public:
  // `radiosity` and `direct` per vertex of `mesh` (as radiosity_state keeps
  // them; `direct` may be empty: then indirect = reflected). `ambient`
  // (ambient_radiosity of the state) stands in for the light still unshot:
  // each vertex reflects rho times it, as the live view shows it.
  // `caustic` (may be empty) is the state's part of B by way of mirrors
  // and glass. The mesh must outlive the field.
  radiosity_field(const patch_mesh& mesh, std::span<const rgb> radiosity, std::span<const rgb> direct,
                  const rgb& ambient = rgb(0.0), std::span<const rgb> caustic = {});
  ~radiosity_field();
  radiosity_field(const radiosity_field&) = delete;
  radiosity_field& operator=(const radiosity_field&) = delete;

  // The solution at `point` on `surface` (front side), whose normal there
  // is `normal` (either way round, any length); zero where the surface has
  // no elements.
  diffuse_radiosity at(int surface, const vec3& point, const vec3& normal) const;

  const patch_mesh& mesh() const { return mesh_; }

 private:
  const patch_mesh& mesh_;
  std::vector<diffuse_radiosity> vertex_values_;
  struct embree_state;
  std::unique_ptr<embree_state> state_;
};

}  // namespace bounce
