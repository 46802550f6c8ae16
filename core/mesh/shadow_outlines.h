// Shadow outlines: the umbra and penumbra boundaries (D1/D2
// discontinuities; Heckbert 1992, Lischinski, Tampieri & Greenberg 1992)
// of the lights that carry the power, made edges of the mesh before it is
// refined. Across a penumbra's edge the radiance's slope jumps, and across
// a point light's shadow edge the radiance itself; an element that
// straddles one is drawn by linear interpolation over a kink, which no
// refinement of that element removes until it is pixel-sized. With the
// outline in the mesh, elements end where the light changes.
//
// Which shadows: those of the strongest lights, when at most
// shadow_outline_max_lights of them carry shadow_outline_power_share of
// the direct power (a Cornell box, a room with one lamp, a sun); a scene lit
// by many equal lamps gets none, its shadows overlap softly. Occluders are
// convex parts (a connected part of a surface whose vertices all lie on one
// side of each of its faces: boxes, blocks, panels, spheres), clipped to the
// receiving plane's front, so a tall box casts on a low one beside it.
// Receivers are flat surfaces facing the light. The outlines are exact for
// a convex occluder and a convex light polygon (a light's corners, its
// convex hull): the penumbra is the convex hull of the occluder projected
// from every light corner onto the receiving plane, the umbra the
// intersection of those projections. In a plane, the penumbrae and umbrae
// of all occluders are united before cutting, so only the outer boundaries
// stay (Drettakis 1994's maximal ones): an outline inside another
// occluder's umbra is dropped. Shadows whose penumbra is smaller than
// `smallest_shadow` are not outlined: they would make elements below the
// mesh's size.
//
// Each receiving triangle the outlines cross is split into three regions
// (umbra, penumbra, lit), each triangulated on the plane's integer frame as
// the coplanar cut does (plane_pieces.h); the piece keeps its vertices, so
// its boundary still meets its neighbours.
#pragma once

#include <cstddef>
#include <vector>

#include "scene/scene.h"
#include "scene/tessellate.h"

namespace bounce {

inline constexpr double shadow_outline_power_share = 0.8;
inline constexpr std::size_t shadow_outline_max_lights = 8;
// Shadows across less than this fraction of an element are not outlined.
inline constexpr double shadow_outline_smallest = 0.1;

struct shadow_outline_stats {
  std::size_t lights = 0;           // lights whose shadows were outlined
  std::size_t shadows = 0;          // (light, occluder, plane) shadows outlined
  std::size_t triangles_split = 0;  // receiving triangles replaced by their regions
  std::size_t triangles_left = 0;   // crossed triangles whose regions could not be triangulated: left whole
  std::size_t triangles_added = 0;  // triangles that replaced them
};

// Splits the flat surfaces' triangles (tessellated[i] is surface i's; only
// those with flat[i] receive) along the shadow outlines of the strong
// lights: emitting flat surfaces and point lights.
shadow_outline_stats cut_shadow_outlines(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                         const std::vector<material>& materials,
                                         const std::vector<punctual_light>& lights, double scene_diagonal,
                                         double smallest_shadow);

}  // namespace bounce
