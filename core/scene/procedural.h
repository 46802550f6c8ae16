// Procedural scenes for the `scale` bench suite: built in code, no files,
// deterministic on every platform (a fixed-seed integer hash, no <random>
// distributions, whose output is implementation-defined).
//
// Both are closed rooms seen from inside, y up, lit by rectangular ceiling
// emitters set flush into the ceiling (the ceiling is cut around them, so
// nothing overlaps). Every face is counter-clockwise seen from its visible
// side: walls, floor and ceiling face into the room, objects face out.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// A 10 x 3 x 10 room (x and z in [-5, 5], floor at y = 0) with a 2 x 2
// ceiling light and boxes_per_side^2 boxes in a jittered grid on the floor,
// 0.2 to 1.2 high. A box has no bottom face: 5 quads, 10 triangles. The
// room adds 28 triangles (its ceiling is 8 quads around the light).
// Open: without the wall behind the camera (26 triangles for the room),
// so that light leaves the room. boxes_per_side >= 1.
scene make_box_room(int boxes_per_side, bool open = false);

// make_box_room's triangles: the room's, plus so many per box.
inline constexpr std::size_t box_room_fixed_triangles = 28;
inline constexpr std::size_t box_room_triangles_per_box = 10;

// A floor of furnished rooms (6 x 3 x 5 each, connected by doors through
// 0.2 thick walls): tables, chairs, shelves, sideboards, lamps, vases and
// balls. Curved objects are smooth polygon meshes (per-corner normals)
// whose tessellation, and the number of rooms, grow with the target: the
// scene has target_triangles within 1% for targets from
// interior_min_triangles to interior_max_triangles (below, it has the
// fewest it can: 2 rooms at the coarsest tessellation, about 3,000). About
// 1 room per 40,000 triangles; furniture and doors keep clear of each other
// and of the walls, so nothing intersects or overlaps.
scene make_interior(std::size_t target_triangles);

inline constexpr std::size_t interior_min_triangles = 3'000;
inline constexpr std::size_t interior_max_triangles = 20'000'000;

// Triangles the scene's polygon meshes make: an n-gon counts n - 2.
// Other shapes (spheres, patches) count 0: they have no fixed tessellation.
std::size_t triangle_count(const scene& s);

// Builds a procedural scene by name: "box-room-<boxes per side>" (1 to
// 1000), "box-room-open-<boxes per side>" or "interior-<triangles>" with an optional k (1,000) or m
// (1,000,000) suffix, e.g. "box-room-60", "interior-100k", "interior-1m".
// False with `error` naming the name when it is none of these.
bool make_procedural_scene(std::string_view name, scene& out, std::string& error);

// A walk through a scene make_procedural_scene built (s.source names it):
// `views` cameras with the scene camera's field of view and size, at even
// steps along a path that stays clear of everything. A box room: once
// round a circle of radius 3.5 about the centre, 1.8 high, each camera
// looking ahead across the boxes. An interior: along the first row of
// rooms through their doors (0.9 from the rooms' north walls, 1.6 high),
// looking ahead and down towards the tables. Empty for any other scene.
std::vector<camera> procedural_walk(const scene& s, int views);

}  // namespace bounce
