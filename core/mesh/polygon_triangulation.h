// Triangulation of a polygon with holes on integer points, for the cuts of
// flat surfaces (coplanar_cut.h, shadow_outlines.h).
#pragma once

#include <array>
#include <vector>

namespace bounce {

// Triangulates a simple polygon with holes, given as integer points (exact
// orientation tests): `outer` counter-clockwise, each hole clockwise, none
// touching another. Returns corner triples, counter-clockwise, indexing the
// concatenation of outer and the holes in order: ear clipping, then
// Lawson's flips to a constrained Delaunay triangulation (the polygon's and
// the holes' edges kept), which has no slivers the points do not force.
struct int_point {
  long long x = 0, y = 0;
  bool operator==(const int_point&) const = default;
};
std::vector<std::array<int, 3>> triangulate_with_holes(const std::vector<int_point>& outer,
                                                       const std::vector<std::vector<int_point>>& holes);

}  // namespace bounce
