// Coplanar overlaps: a surface lying in (or within a hair of) the plane of
// another surface that faces the same way, such as a light set into a
// ceiling or 0.1 mm under it, as most Cornell box files have it. Both the
// radiosity mesh and the ray scene would hold two coincident surfaces
// there: the Gouraud view z-fights, the covered part of the surface behind
// receives light it could never get, and ray hits flip between the two.
// The covered part is cut out of the surface behind, as the embedded
// Cornell box does by hand.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "mesh/polygon_triangulation.h"
#include "scene/scene.h"
#include "scene/tessellate.h"

namespace bounce {

// Two planes facing the same way are one plane when their offsets differ by
// at most this fraction of the scene's bounding-box diagonal (0.48 mm in the
// 550 mm Cornell box, whose diagonal is 965 mm) and their normals by at
// most coplanar_max_angle radians.
inline constexpr double coplanar_relative_tolerance = 5e-4;
inline constexpr double coplanar_max_angle = 1e-3;

struct coplanar_cut_stats {
  std::size_t surfaces_cut = 0;       // (surface, material) pieces that lost area
  double area_removed = 0.0;          // scene units squared
  std::size_t pieces_left_uncut = 0;  // covered pieces whose remainder could not be triangulated: left whole
  // The work done: polygons of the cover a piece was clipped against,
  // summed over the pieces. Merging keeps it near the number of pieces,
  // however many of them overlap.
  std::size_t polygons_clipped_against = 0;
};

// Cuts coplanar overlaps out of the triangles of flat surfaces, in place.
// tessellated[i] holds surface i's triangles; only surfaces with flat[i]
// (polygon meshes) take part, curved ones are left alone. Triangles are
// grouped into planes (normal within coplanar_max_angle, offset within the
// tolerance); within a plane, a (surface, material) piece is covered by the
// pieces ranked above it: emitters first (an emitter keeps all its area),
// then the piece in front (the larger offset along the common normal), then
// the later surface. A covered piece's triangles whose boxes overlap the
// cover are replaced by a triangulation of their union minus the cover
// (Clipper's polygon difference, then ear clipping with holes bridged;
// the rest of the piece stays as it is): vertices on
// the region's boundary are kept exactly, so the piece still meets its
// other faces without T-vertices; new vertices (where the cover's outline
// crosses) interpolate position, normal and uv from the triangle they lie
// in. Pieces the cover only touches are left as they are.
coplanar_cut_stats cut_coplanar_overlaps(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                         const std::vector<material>& materials, double scene_diagonal);

// Contacts: a solid standing on a flat surface (a box on a floor, a table
// leg on a rug) hides the ground under it, which no light reaches and no
// eye sees. Left in the mesh, that ground takes its share of the light
// that reaches the elements around it and keeps it: a coarse link's
// irradiance is spread over all the elements under its receiver, hidden
// ones included, and what they reflect is blocked. The ground under
// solids is cut out along the contact outline, so no element straddles
// the contact and no hidden vertex enters the interpolation.
//
// The outline is where the solid's faces cross the plane lifted by
// contact_lift of the scene's diagonal (above the coplanar tolerance): each
// crossing triangle gives a segment with the solid's inside on its left,
// and the segments are chained into loops. A counter-clockwise loop (an
// outward-facing solid's; the room's walls give clockwise ones) whose
// inside is closed above (straight up from inside, the first face is met
// from behind) is cut out of every piece of the plane. A solid that does
// not reach down to the lifted plane (a box 2 cm up in a 10 m room) is not
// in contact and cuts nothing; an open tube cuts nothing either. The
// search looks as far again as each connected part of a plane reaches: a
// solid that overhangs a part by more (a table top over its legs' tops)
// leaves its loop open there and cuts nothing.
inline constexpr double contact_lift = 1e-3;

struct contact_cut_stats {
  std::size_t footprints = 0;                // loops cut out (counted in the planes where they cut something)
  std::size_t pieces_cut = 0;                // (surface, material) pieces that lost area
  double area_removed = 0.0;                 // scene units squared
  std::size_t pieces_left_uncut = 0;         // pieces whose remainder could not be triangulated: left whole
  std::vector<std::array<vec3, 2>> outline;  // the loops' edges, in the plane cut
};

// Cuts the ground under solids out of the triangles of flat surfaces, in
// place (tessellated and flat as for cut_coplanar_overlaps; every surface,
// flat or curved, can stand on them).
// Connected parts of a plane whose box's diagonal is below `smallest_part`
// are left alone (the mesher passes a tenth of its element size).
contact_cut_stats cut_buried_contacts(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                      double scene_diagonal, double smallest_part);

}  // namespace bounce
