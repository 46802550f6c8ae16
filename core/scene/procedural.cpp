// Procedural bench scenes (procedural.h). Geometry goes through a builder
// that either stores faces, one polygon mesh per material, or only counts
// the triangles they would make: make_interior sizes its tessellation by
// counting (cheap: no vertices), then builds once.
#include "scene/procedural.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <vector>

#include "base/check.h"
#include "base/random_stream.h"

namespace bounce {
namespace {

using std::numbers::pi;

// A number in [0, 1) that depends only on its arguments.
double hash01(std::uint64_t a, std::uint64_t b, std::uint64_t c = 0, std::uint64_t d = 0) {
  const std::uint64_t h = mix64(a ^ mix64(b ^ mix64(c ^ mix64(d))));
  return unit_interval(h);
}

// A point of a surface of revolution's profile: radius and height, and the
// outward normal in the (r, y) plane.
struct profile_point {
  double r = 0.0, y = 0.0;
  double nr = 1.0, ny = 0.0;
};
// Pieces of rings; the rings of a piece share vertices (one smooth surface),
// pieces meet at creases.
using profile = std::vector<std::vector<profile_point>>;

// `rings` samples of the curve f(t) = (r, y), t in [0, 1], with normals
// from its tangent (rotated clockwise: outward for a curve going up).
template <class F>
std::vector<profile_point> sample_profile(int rings, F f) {
  std::vector<profile_point> out;
  const double h = 1e-4;
  for (int k = 0; k < rings; ++k) {
    const double t = double(k) / (rings - 1);
    const vec2 p = f(t);
    const vec2 tangent = f(std::min(t + h, 1.0)) - f(std::max(t - h, 0.0));
    const vec2 n = glm::normalize(vec2(tangent.y, -tangent.x));
    out.push_back({p.x, p.y, n.x, n.y});
  }
  return out;
}

enum box_face : unsigned { pos_x = 1, neg_x = 2, pos_y = 4, neg_y = 8, pos_z = 16, neg_z = 32 };
constexpr unsigned all_faces = 63;
constexpr unsigned no_bottom = all_faces & ~neg_y;  // stands on something
constexpr unsigned sides_only = pos_x | neg_x | pos_z | neg_z;

// Collects faces, one polygon mesh per material; when count_only, only
// the number of triangles they make (an n-gon makes n - 2).
struct builder {
  bool count_only = false;
  std::size_t triangles = 0;
  std::vector<polygon_mesh> meshes;  // by material

  builder(std::size_t materials, bool count) : count_only(count), meshes(count ? 0 : materials) {}

  // A flat polygon, counter-clockwise seen from the side it faces.
  void polygon(int material, std::initializer_list<vec3> corners) {
    triangles += corners.size() - 2;
    if (count_only) return;
    polygon_mesh& m = meshes[material];
    polygon_face f;
    f.material = material;
    for (const vec3& p : corners) {
      f.position.push_back(int(m.positions.size()));
      m.positions.push_back(p);
    }
    m.faces.push_back(std::move(f));
  }

  // The parallelogram o, o+u, o+u+v, o+v: it faces u x v.
  void rect(int material, const vec3& o, const vec3& u, const vec3& v) {
    polygon(material, {o, o + u, o + u + v, o + v});
  }

  // An axis-aligned box's faces (box_face bits), facing out.
  void box(int material, const vec3& lo, const vec3& hi, unsigned faces) {
    const vec3 x(hi.x - lo.x, 0, 0), y(0, hi.y - lo.y, 0), z(0, 0, hi.z - lo.z);
    if (faces & pos_x) rect(material, {hi.x, lo.y, lo.z}, y, z);
    if (faces & neg_x) rect(material, lo, z, y);
    if (faces & pos_y) rect(material, {lo.x, hi.y, lo.z}, z, x);
    if (faces & neg_y) rect(material, lo, x, z);
    if (faces & pos_z) rect(material, {lo.x, lo.y, hi.z}, x, y);
    if (faces & neg_z) rect(material, lo, y, x);
  }

  // A surface of revolution about the vertical axis through `base`, with
  // per-corner normals; flat caps optionally close the first ring (facing
  // down) and the last one (facing up).
  void lathe(int material, const vec3& base, const profile& pieces, int around, bool cap_bottom, bool cap_top) {
    for (const auto& piece : pieces) triangles += 2 * std::size_t(around) * (piece.size() - 1);
    triangles += std::size_t(cap_bottom + cap_top) * (around - 2);
    if (count_only) return;
    polygon_mesh& m = meshes[material];
    std::vector<double> c(around), s(around);
    for (int j = 0; j < around; ++j) {
      c[j] = std::cos(2.0 * pi * j / around);
      s[j] = std::sin(2.0 * pi * j / around);
    }
    int first_ring = -1, last_ring = -1;  // position index of the caps' rings
    for (const auto& piece : pieces) {
      const int p0 = int(m.positions.size()), n0 = int(m.normals.size());
      for (const profile_point& q : piece)
        for (int j = 0; j < around; ++j) {
          m.positions.push_back(base + vec3(q.r * c[j], q.y, q.r * s[j]));
          m.normals.push_back(glm::normalize(vec3(q.nr * c[j], q.ny, q.nr * s[j])));
        }
      if (first_ring < 0) first_ring = p0;
      last_ring = p0 + int(piece.size() - 1) * around;
      const auto at = [&](std::size_t k, int j) { return int(k) * around + j % around; };
      for (std::size_t k = 0; k + 1 < piece.size(); ++k)
        for (int j = 0; j < around; ++j) {
          polygon_face f;
          f.material = material;
          for (int i : {at(k, j), at(k + 1, j), at(k + 1, j + 1), at(k, j + 1)}) {
            f.position.push_back(p0 + i);
            f.normal.push_back(n0 + i);
          }
          m.faces.push_back(std::move(f));
        }
    }
    const auto cap = [&](int ring, bool up) {
      polygon_face f;
      f.material = material;
      for (int j = 0; j < around; ++j) f.position.push_back(ring + (up ? around - 1 - j : j));
      m.faces.push_back(std::move(f));
    };
    if (cap_bottom) cap(first_ring, false);
    if (cap_top) cap(last_ring, true);
  }

  // A latitude-longitude sphere with per-corner normals: `bands` from pole
  // to pole, `around` segments; triangles at the poles, quads between.
  void ball(int material, const vec3& centre, double radius, int bands, int around) {
    triangles += 2 * std::size_t(around) * (bands - 1);
    if (count_only) return;
    polygon_mesh& m = meshes[material];
    const int p0 = int(m.positions.size()), n0 = int(m.normals.size());
    const auto add = [&](double theta, double phi) {
      const vec3 dir(std::sin(theta) * std::cos(phi), -std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(centre + radius * dir);
      m.normals.push_back(dir);
    };
    add(0.0, 0.0);  // south pole: index 0
    for (int k = 1; k < bands; ++k)
      for (int j = 0; j < around; ++j) add(pi * k / bands, 2.0 * pi * j / around);
    add(pi, 0.0);  // north pole
    const int north = 1 + (bands - 1) * around;
    const auto ring = [&](int k, int j) { return 1 + (k - 1) * around + j % around; };
    const auto face = [&](std::initializer_list<int> corners) {
      polygon_face f;
      f.material = material;
      for (int i : corners) {
        f.position.push_back(p0 + i);
        f.normal.push_back(n0 + i);
      }
      m.faces.push_back(std::move(f));
    };
    for (int j = 0; j < around; ++j) {
      face({0, ring(1, j), ring(1, j + 1)});
      for (int k = 1; k + 1 < bands; ++k) face({ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)});
      face({ring(bands - 1, j), north, ring(bands - 1, j + 1)});
    }
  }

  // A wall from `origin` (on the floor) along the horizontal unit vector
  // `along`: it faces along x up. With door_end > door_start, a door opening
  // door_height high between those distances along the wall.
  void wall(int material, const vec3& origin, const vec3& along, double length, double height, double door_start = 0.0,
            double door_end = 0.0, double door_height = 0.0) {
    const vec3 up(0, 1, 0);
    if (door_end <= door_start) return rect(material, origin, along * length, up * height);
    const auto at = [&](double s, double y) { return origin + s * along + y * up; };
    polygon(material, {at(0, 0), at(door_start, 0), at(door_start, door_height), at(door_end, door_height),
                       at(door_end, 0), at(length, 0), at(length, height), at(0, height)});
  }

  // The ceiling at height y over the grid xs x zs (4 lines each), facing
  // down: the middle cell is the light, the 8 around it the ceiling. They
  // share whole edges: nothing overlaps, no corner lies on another's edge.
  void ceiling(int ceiling_material, int light_material, const double (&xs)[4], const double (&zs)[4], double y) {
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c)
        rect(a == 1 && c == 1 ? light_material : ceiling_material, {xs[a], y, zs[c]}, {xs[a + 1] - xs[a], 0, 0},
             {0, 0, zs[c + 1] - zs[c]});
  }

  // The scene's surfaces: one per material that has faces.
  void finish(scene& s) {
    for (std::size_t m = 0; m < meshes.size(); ++m)
      if (!meshes[m].faces.empty()) s.surfaces.push_back({s.materials[m].name, "", std::move(meshes[m])});
  }
};

material diffuse(const std::string& name, rgb rho) {
  material m;
  m.name = name;
  m.rho = rho;
  return m;
}

material emitter(const std::string& name, rgb ke) {
  material m = diffuse(name, rgb(0.5));
  m.ke = ke;
  return m;
}

// --- The interior ----------------------------------------------------------

// Rooms are room_w x room_h x room_d inside, in a grid, wall_t apart; each
// neighbour pair is joined by a door through the wall between them.
constexpr double room_w = 6.0, room_d = 5.0, room_h = 3.0, wall_t = 0.2;
constexpr double door_h = 2.1;
// Doors sit 0.4 to 1.4 from a room's north-east corner, on all four walls;
// the furniture keeps clear of them.
constexpr double door_near = 0.4, door_far = 1.4;
// Triangles a room holds on average at the full tessellation steps: the
// number of rooms grows with the target so that objects stay moderate.
constexpr double triangles_per_room = 40'000.0;

enum interior_material : int {
  floor_m,
  wall_m,
  ceiling_m,
  light_m,
  wood_m,
  fabric_m,
  shelf_m,
  metal_m,
  shade_m,
  red_m,
  blue_m,
  white_m,
  green_m,
  interior_materials
};

std::vector<material> interior_palette() {
  return {diffuse("floor", {0.55, 0.42, 0.3}),       diffuse("wall", {0.75, 0.73, 0.68}),
          diffuse("ceiling", {0.8, 0.8, 0.8}),       emitter("light", rgb(8.0)),
          diffuse("wood", {0.45, 0.3, 0.18}),        diffuse("fabric", {0.3, 0.4, 0.6}),
          diffuse("shelf", {0.65, 0.58, 0.45}),      diffuse("metal", {0.4, 0.4, 0.42}),
          diffuse("shade", {0.78, 0.74, 0.6}),       diffuse("ceramic red", {0.7, 0.25, 0.2}),
          diffuse("ceramic blue", {0.2, 0.35, 0.7}), diffuse("ceramic white", {0.8, 0.78, 0.75}),
          diffuse("green", {0.3, 0.6, 0.3})};
}

struct interior_layout {
  int rooms_x = 2, rooms_z = 1;
  // Tessellation steps, handed to the curved objects in turn: object i of
  // n has detail / n steps, one more if i < detail % n.
  std::size_t detail = 0;
  std::size_t objects = 1;  // curved objects in the building
};

constexpr std::uint64_t interior_seed = 0x1b0c5e;

struct interior_builder {
  builder& b;
  const interior_layout& layout;
  std::size_t next_object = 0;
  vec3 first_table{0.0};  // the camera looks at room (0, 0)'s table

  int level() {
    const std::size_t i = next_object++ % layout.objects;
    return int(layout.detail / layout.objects + (i < layout.detail % layout.objects ? 1 : 0));
  }
  static int around(int level) { return 8 + 2 * level; }

  // A vase standing at `base`: a belly and a narrower neck, closed on top.
  void vase(int material, const vec3& base, double radius, double height) {
    const int l = level();
    const auto f = [&](double t) { return vec2(radius * (0.5 + 0.5 * std::sin(pi * (0.1 + 0.9 * t))), height * t); };
    b.lathe(material, base, {sample_profile(3 + l, f)}, around(l), false, true);
  }

  // A bottle: a cylinder, a rounded shoulder and a neck, closed on top.
  void bottle(int material, const vec3& base, double radius, double height) {
    const int l = level();
    const auto body = [&](double t) { return vec2(radius, 0.6 * height * t); };
    const auto shoulder = [&](double t) {
      return vec2(radius * (0.35 + 0.65 * std::cos(0.5 * pi * t)), height * (0.6 + 0.2 * std::sin(0.5 * pi * t)));
    };
    const auto neck = [&](double t) { return vec2(0.35 * radius, height * (0.8 + 0.2 * t)); };
    b.lathe(material, base, {sample_profile(2, body), sample_profile(3 + l / 2, shoulder), sample_profile(2, neck)},
            around(l), false, true);
  }

  // A ball resting on the surface at `base`.
  void ball(int material, const vec3& base, double radius) {
    const int l = level();
    b.ball(material, base + vec3(0, radius, 0), radius, 4 + l, around(l));
  }

  // A lamp: a round foot, a pole and a closed shade (the pole ends under it).
  void lamp(const vec3& base, double foot_r, double foot_h, double pole_r, double pole_h, double shade_r0,
            double shade_r1, double shade_h) {
    const int l = level();
    const auto foot = [&](double t) { return vec2(foot_r, foot_h * t); };
    const auto foot_top = [&](double t) { return vec2(foot_r + (pole_r - foot_r) * t, foot_h); };
    const auto pole = [&](double t) { return vec2(pole_r, foot_h + (pole_h - foot_h) * t); };
    b.lathe(metal_m, base, {sample_profile(2, foot), sample_profile(2, foot_top), sample_profile(2, pole)}, around(l),
            false, false);
    const auto shade = [&](double t) { return vec2(shade_r0 + (shade_r1 - shade_r0) * t, pole_h + shade_h * t); };
    b.lathe(shade_m, base, {sample_profile(2, shade)}, around(l), true, true);
  }

  // A small object on a surface at `base`, of a kind and colour the hash picks.
  void ornament(const vec3& base, std::uint64_t key, double max_height) {
    const int material = red_m + int(hash01(interior_seed, key, 1) * 4.0);  // the ceramics and green
    const double r = hash01(interior_seed, key, 2);
    switch (int(hash01(interior_seed, key, 3) * 3.0)) {
      case 0:
        ball(material, base, 0.06 + 0.03 * r);
        break;
      case 1:
        vase(material, base, 0.07 + 0.02 * r, std::min(max_height, 0.18 + 0.1 * r));
        break;
      default:
        bottle(material, base, 0.045 + 0.015 * r, std::min(max_height, 0.2 + 0.1 * r));
        break;
    }
  }

  // A chair whose sitter faces +z (facing > 0) or -z; the backrest is behind.
  void chair(double cx, double cz, int facing) {
    const double seat = 0.43, top = 0.47, half = 0.21;
    b.box(fabric_m, {cx - half, seat, cz - half}, {cx + half, top, cz + half}, all_faces);
    for (double sx : {-1.0, 1.0})
      for (double sz : {-1.0, 1.0}) {
        const double lx = cx + sx * 0.18, lz = cz + sz * 0.18;  // legs 0.04 wide, 0.01 inside the seat
        b.box(wood_m, {lx - 0.02, 0, lz - 0.02}, {lx + 0.02, seat, lz + 0.02}, sides_only);
      }
    const double back = facing > 0 ? cz - 0.18 : cz + 0.18;
    b.box(wood_m, {cx - 0.2, top, back - 0.02}, {cx + 0.2, 0.95, back + 0.02}, no_bottom);
  }

  // A table 1.6 x 0.9, 0.76 high, centred at (cx, cz), with things on it.
  void table(double cx, double cz, std::uint64_t key) {
    const double top = 0.76, under = 0.72;
    b.box(wood_m, {cx - 0.8, under, cz - 0.45}, {cx + 0.8, top, cz + 0.45}, all_faces);
    for (double sx : {-1.0, 1.0})
      for (double sz : {-1.0, 1.0}) {
        const double lx = cx + sx * 0.73, lz = cz + sz * 0.38;
        b.box(wood_m, {lx - 0.03, 0, lz - 0.03}, {lx + 0.03, under, lz + 0.03}, sides_only);
      }
    vase(red_m + int(hash01(interior_seed, key, 4) * 3.0), {cx - 0.45, top, cz}, 0.1, 0.35);
    ball(green_m, {cx, top, cz + 0.15}, 0.08);
    vase(white_m, {cx + 0.45, top, cz - 0.1}, 0.14, 0.14);
  }

  // A shelf 1.8 wide, 0.35 deep, 1.8 high, its back at z = z0 + 0.05.
  void shelf(double x0, double z0, std::uint64_t key) {
    const double sx = x0, sz = z0 + 0.05, height = 1.8;
    b.box(shelf_m, {sx, 0, sz}, {sx + 0.02, height, sz + 0.35}, no_bottom);
    b.box(shelf_m, {sx + 1.78, 0, sz}, {sx + 1.8, height, sz + 0.35}, no_bottom);
    // Boards span between the sides (their ends touch them: no end faces).
    const unsigned board = pos_y | neg_y | pos_z | neg_z;
    for (int k = 0; k < 5; ++k) {
      const double y0 = k < 4 ? 0.02 + 0.44 * k : 1.74;
      b.box(shelf_m, {sx + 0.02, y0, sz + 0.01}, {sx + 1.78, y0 + 0.03, sz + 0.34}, board);
      const int slots = k < 4 ? 3 : 2;
      for (int i = 0; i < slots; ++i) {
        const double x = k < 4 ? sx + 0.35 + 0.55 * i : sx + 0.6 + 0.6 * i;
        ornament({x, y0 + 0.03, sz + 0.175}, key * 16 + std::uint64_t(k * 3 + i), 0.3);
      }
    }
  }

  void room(int i, int j) {
    const double x0 = i * (room_w + wall_t), z0 = j * (room_d + wall_t);
    const double x1 = x0 + room_w, z1 = z0 + room_d;
    const bool east = i + 1 < layout.rooms_x, west = i > 0, north = j + 1 < layout.rooms_z, south = j > 0;
    const std::uint64_t key = std::uint64_t(j) * 65536 + std::uint64_t(i);

    b.rect(floor_m, {x0, 0, z0}, {0, 0, room_d}, {room_w, 0, 0});
    const double xs[4] = {x0, x0 + 2.4, x0 + 3.6, x1}, zs[4] = {z0, z0 + 2.0, z0 + 3.0, z1};  // a 1.2 x 1.0 light
    b.ceiling(ceiling_m, light_m, xs, zs, room_h);
    // Walls face into the room; a door opening where a neighbour is.
    const auto door = [&](bool open, double s0, double s1) { return open ? std::pair(s0, s1) : std::pair(0.0, 0.0); };
    const auto [s0, s1] = door(south, room_w - door_far, room_w - door_near);
    b.wall(wall_m, {x0, 0, z0}, {1, 0, 0}, room_w, room_h, s0, s1, door_h);
    const auto [n0, n1] = door(north, door_near, door_far);
    b.wall(wall_m, {x1, 0, z1}, {-1, 0, 0}, room_w, room_h, n0, n1, door_h);
    const auto [w0, w1] = door(west, door_near, door_far);
    b.wall(wall_m, {x0, 0, z1}, {0, 0, -1}, room_d, room_h, w0, w1, door_h);
    const auto [e0, e1] = door(east, room_d - door_far, room_d - door_near);
    b.wall(wall_m, {x1, 0, z0}, {0, 0, 1}, room_d, room_h, e0, e1, door_h);
    // The passages through the walls, made by the room west or south of them.
    if (east) {
      const double za = z1 - door_far, zb = z1 - door_near;
      b.rect(wall_m, {x1, 0, za}, {wall_t, 0, 0}, {0, door_h, 0});
      b.rect(wall_m, {x1, 0, zb}, {0, door_h, 0}, {wall_t, 0, 0});
      b.rect(wall_m, {x1, door_h, za}, {wall_t, 0, 0}, {0, 0, zb - za});
      b.rect(floor_m, {x1, 0, za}, {0, 0, zb - za}, {wall_t, 0, 0});
    }
    if (north) {
      const double xa = x1 - door_far, xb = x1 - door_near;
      b.rect(wall_m, {xa, 0, z1}, {0, door_h, 0}, {0, 0, wall_t});
      b.rect(wall_m, {xb, 0, z1}, {0, 0, wall_t}, {0, door_h, 0});
      b.rect(wall_m, {xa, door_h, z1}, {xb - xa, 0, 0}, {0, 0, wall_t});
      b.rect(floor_m, {xa, 0, z1}, {0, 0, wall_t}, {xb - xa, 0, 0});
    }

    // Furniture, clear of the doors (all within 1.6 of the north-east
    // corner's walls) and of the walls by at least 0.05.
    const double cx = x0 + 2.6 + 0.3 * (hash01(interior_seed, key, 10) - 0.5);
    const double cz = z0 + 2.3 + 0.3 * (hash01(interior_seed, key, 11) - 0.5);
    if (i == 0 && j == 0) first_table = {cx, 0.76, cz};
    table(cx, cz, key);
    for (double dx : {-0.4, 0.4}) {
      chair(cx + dx, cz - 0.76, 1);
      chair(cx + dx, cz + 0.76, -1);
    }
    shelf(x0 + 0.3, z0, key);
    // A sideboard along the west wall with a lamp and ornaments on it.
    const double top = 0.8;
    b.box(shelf_m, {x0 + 0.05, 0, z0 + 1.0}, {x0 + 0.55, top, z0 + 2.8}, no_bottom);
    lamp({x0 + 0.3, top, z0 + 1.35}, 0.1, 0.03, 0.012, 0.45, 0.18, 0.11, 0.22);
    ball(green_m, {x0 + 0.3, top, z0 + 1.9}, 0.1);
    vase(blue_m, {x0 + 0.3, top, z0 + 2.45}, 0.12, 0.4);
    // A floor lamp and a floor vase along the east wall.
    lamp({x1 - 0.45, 0, z0 + 2.9}, 0.2, 0.04, 0.02, 1.5, 0.25, 0.15, 0.3);
    vase(red_m + int(hash01(interior_seed, key, 12) * 3.0), {x1 - 0.45, 0, z0 + 1.8}, 0.22, 0.7);
  }

  void build() {
    for (int j = 0; j < layout.rooms_z; ++j)
      for (int i = 0; i < layout.rooms_x; ++i) room(i, j);
  }
};

std::size_t count_interior(const interior_layout& layout) {
  builder b(interior_materials, true);
  interior_builder ib{b, layout};
  ib.build();
  return b.triangles;
}

// Rooms from the target, then the smallest detail whose count reaches the
// target, or the one below when that is closer.
interior_layout plan_interior(std::size_t target) {
  interior_layout layout;
  const int rooms = std::max(2, int(std::llround(double(target) / triangles_per_room)));
  layout.rooms_x = int(std::ceil(std::sqrt(double(rooms))));
  layout.rooms_z = (rooms + layout.rooms_x - 1) / layout.rooms_x;
  {
    builder b(interior_materials, true);
    interior_builder ib{b, layout};
    ib.build();
    layout.objects = ib.next_object;
  }
  const auto count = [&](std::size_t detail) {
    layout.detail = detail;
    return count_interior(layout);
  };
  if (count(0) >= target) {
    layout.detail = 0;
    return layout;
  }
  std::size_t low = 0, high = 1;  // count(low) < target <= count(high)
  while (count(high) < target) {
    low = high;
    high *= 2;
  }
  while (high - low > 1) {
    const std::size_t mid = low + (high - low) / 2;
    (count(mid) < target ? low : high) = mid;
  }
  layout.detail = target - count(low) < count(high) - target ? low : high;
  return layout;
}

// Digits, with an optional k (1,000) or m (1,000,000) suffix.
bool parse_count(std::string_view text, std::uint64_t& out) {
  std::uint64_t scale = 1;
  if (!text.empty() && (text.back() == 'k' || text.back() == 'K')) scale = 1'000;
  if (!text.empty() && (text.back() == 'm' || text.back() == 'M')) scale = 1'000'000;
  if (scale != 1) text.remove_suffix(1);
  if (text.empty()) return false;
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return false;
  if (value > UINT64_MAX / scale) return false;
  out = value * scale;
  return true;
}

}  // namespace

scene make_box_room(int boxes_per_side, bool open) {
  BOUNCE_CHECK(boxes_per_side >= 1);
  const int n = boxes_per_side;
  scene s;
  s.source = (open ? "box-room-open-" : "box-room-") + std::to_string(n);
  s.materials = {diffuse("floor", rgb(0.6)),           diffuse("wall", {0.7, 0.7, 0.65}),
                 diffuse("ceiling", rgb(0.75)),        emitter("light", rgb(8.0)),
                 diffuse("box red", {0.7, 0.3, 0.25}), diffuse("box green", {0.3, 0.6, 0.35}),
                 diffuse("box blue", {0.3, 0.4, 0.7}), diffuse("box white", rgb(0.78))};
  enum { floor_m, wall_m, ceiling_m, light_m, first_box_m };
  const int box_materials = int(s.materials.size()) - first_box_m;
  builder b(s.materials.size(), false);
  const double half = 5.0, height = 3.0;
  b.rect(floor_m, {-half, 0, -half}, {0, 0, 2 * half}, {2 * half, 0, 0});
  b.wall(wall_m, {-half, 0, -half}, {1, 0, 0}, 2 * half, height);
  if (!open) b.wall(wall_m, {half, 0, half}, {-1, 0, 0}, 2 * half, height);  // behind the camera
  b.wall(wall_m, {-half, 0, half}, {0, 0, -1}, 2 * half, height);
  b.wall(wall_m, {half, 0, -half}, {0, 0, 1}, 2 * half, height);
  const double lines[4] = {-half, -1.0, 1.0, half};  // a 2 x 2 light: 1/25 of the ceiling
  b.ceiling(ceiling_m, light_m, lines, lines, height);

  // Each box stays inside its grid cell shrunk by 5% on every side, so
  // neighbours never touch.
  const std::uint64_t seed = 0xb0c5;
  const double extent = 4.5, cell = 2.0 * extent / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto h = [&](std::uint64_t k) { return hash01(seed, std::uint64_t(i), std::uint64_t(j), k); };
      const double hx = cell * (0.2 + 0.1 * h(1)), hz = cell * (0.2 + 0.1 * h(2));
      const double top = 0.2 + 1.0 * h(3);
      const double cx = -extent + (i + 0.5) * cell + (0.45 * cell - hx) * (2.0 * h(4) - 1.0);
      const double cz = -extent + (j + 0.5) * cell + (0.45 * cell - hz) * (2.0 * h(5) - 1.0);
      const int material = first_box_m + std::min(int(h(6) * box_materials), box_materials - 1);
      b.box(material, {cx - hx, 0, cz - hz}, {cx + hx, top, cz + hz}, no_bottom);
    }
  b.finish(s);
  s.view.eye = {0, 2.2, 4.6};
  s.view.target = {0, 0.3, 0};
  s.view.fov_y_degrees = 65.0;
  s.view.width = s.view.height = 256;
  return s;
}

scene make_interior(std::size_t target_triangles) {
  const interior_layout layout = plan_interior(target_triangles);
  scene s;
  s.source = "interior-" + std::to_string(target_triangles);
  s.materials = interior_palette();
  builder b(s.materials.size(), false);
  interior_builder ib{b, layout};
  ib.build();
  b.finish(s);
  // From room (0, 0)'s north-east corner (by its doors) towards its table.
  s.view.eye = {room_w - 0.6, 1.7, room_d - 0.6};
  s.view.target = ib.first_table - vec3(0, 0.2, 0);
  s.view.fov_y_degrees = 60.0;
  s.view.width = s.view.height = 256;
  return s;
}

std::size_t triangle_count(const scene& s) {
  std::size_t n = 0;
  for (const surface& surf : s.surfaces)
    if (const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry))
      for (const polygon_face& f : mesh->faces) n += f.position.size() >= 3 ? f.position.size() - 2 : 0;
  return n;
}

std::vector<camera> procedural_walk(const scene& s, int views) {
  std::vector<camera> walk;
  const std::string_view name = s.source;
  std::uint64_t target = 0;
  const bool box_room = name.starts_with("box-room-");
  const bool interior = name.starts_with("interior-") && parse_count(name.substr(9), target);
  if (views < 1 || !(box_room || interior)) return walk;
  for (int k = 0; k < views; ++k) {
    camera c = s.view;
    if (box_room) {
      // Boxes are at most 1.2 high and 4.5 from the centre; the walls are at 5.
      const double a = 2.0 * std::numbers::pi * k / views, ahead = a + 1.75;
      c.eye = {3.5 * std::cos(a), 1.8, 3.5 * std::sin(a)};
      c.target = {2.0 * std::cos(ahead), 0.4, 2.0 * std::sin(ahead)};
    } else {
      // The strip 0.9 from the north walls holds the doors and no furniture.
      const int rooms_x = plan_interior(std::size_t(target)).rooms_x;
      const double x_end = rooms_x * (room_w + wall_t) - wall_t - 0.6;
      const double x = 0.6 + (x_end - 0.6) * k / std::max(1, views - 1);
      c.eye = {x, 1.6, room_d - 0.9};
      c.target = c.eye + vec3(3.0, -0.6, -1.5);
    }
    c.up = {0.0, 1.0, 0.0};
    walk.push_back(c);
  }
  return walk;
}

bool make_procedural_scene(std::string_view name, scene& out, std::string& error) {
  const std::string quoted = "procedural scene '" + std::string(name) + "'";
  constexpr std::string_view box_room = "box-room-", open_room = "box-room-open-", interior = "interior-";
  std::uint64_t value = 0;
  if (name.starts_with(box_room)) {
    const bool open = name.starts_with(open_room);
    const std::string_view text = name.substr(open ? open_room.size() : box_room.size());
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 1 || value > 1000) {
      error = quoted + ": '" + std::string(text) + "' is not a number of boxes per side from 1 to 1000";
      return false;
    }
    out = make_box_room(int(value), open);
    return true;
  }
  if (name.starts_with(interior)) {
    const std::string_view text = name.substr(interior.size());
    if (!parse_count(text, value)) {
      error = quoted + ": '" + std::string(text) +
              "' is not a triangle count (digits with an optional k or m suffix, e.g. interior-100k)";
      return false;
    }
    if (value < interior_min_triangles || value > interior_max_triangles) {
      error = quoted + ": " + std::to_string(value) + " triangles is outside " +
              std::to_string(interior_min_triangles) + " to " + std::to_string(interior_max_triangles);
      return false;
    }
    out = make_interior(std::size_t(value));
    return true;
  }
  error = "unknown " + quoted +
          ": expected box-room-<boxes per side> (e.g. box-room-60), box-room-open-<boxes per side> or "
          "interior-<triangles> (e.g. " +
          "interior-10k, interior-1m)";
  return false;
}

}  // namespace bounce
