// Punctual lights (scene.h's punctual_light): what each sends a point, the
// power it sends out, and photon starts drawn from it. One place for the
// spot's cone and the sun, so that every solver and both tracers agree.
#pragma once

#include "scene/scene.h"

namespace bounce {

// The share of a light's intensity it sends along `from_light` (unit, away
// from the light): 1 for a point light and within a spot's inner cone, 0
// beyond its outer cone, and between them glTF's smooth edge t^2, with t
// running linearly in the cosine from 0 at the outer cone to 1 at the inner.
double cone_share(const punctual_light& l, const vec3& from_light);

// What a light sends a point p: the unit direction toward the light, where
// a shadow ray ends (the light itself; for a sun, a point `far` beyond p
// toward it) and the irradiance on a surface facing the light, before the
// cosine: I share / r^2 for point and spot lights, E for a sun.
struct light_arrival {
  vec3 to_light{0.0};
  vec3 shadow_end{0.0};
  rgb irradiance{0.0};
};
light_arrival light_at(const punctual_light& l, const vec3& p, double far);

// The spot's solid angle weighted by its cone_share, in steradians:
// 2 pi ((1 - cos inner) + (cos inner - cos outer) / 3); 4 pi for a point.
double cone_solid_angle(const punctual_light& l);

// Power the light sends out, per channel: I times cone_solid_angle for
// point and spot lights; E pi r^2 for a sun over a scene within a ball of
// radius `scene_radius` (what can reach the scene).
rgb emitted_power(const punctual_light& l, double scene_radius);

// A photon's start drawn from the light with uniform numbers u1, u2:
// its origin, unit direction and weight, the factor on the mean photon's
// power (emitted_power / count): 1, except across a spot's smooth edge,
// where directions are drawn uniformly in the outer cone and weighted.
// A sun's photons start on the disc of radius `scene_radius`, facing the
// light, just outside the ball about `scene_centre`.
struct light_photon {
  vec3 origin{0.0};
  vec3 direction{0.0};
  double weight = 1.0;
};
light_photon sample_light_photon(const punctual_light& l, const vec3& scene_centre, double scene_radius, double u1,
                                 double u2);

const char* light_type_name(light_type t);

}  // namespace bounce
