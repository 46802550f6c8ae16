#include "radiosity/hierarchical/mirror_chains.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace bounce {
namespace {

std::array<vec3, 8> box_corners(const vec3& lo, const vec3& hi) {
  std::array<vec3, 8> out;
  for (int k = 0; k < 8; ++k) out[k] = vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
  return out;
}

struct interval {
  double lo = INFINITY, hi = -INFINITY;
  void add(double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
};

interval along(const std::array<vec3, 8>& corners, const vec3& axis, double offset = 0.0) {
  interval out;
  for (const vec3& c : corners) out.add(glm::dot(axis, c) - offset);
  return out;
}

void add_mirror(mirror_chain& chain, const planar_mirror& m, int index) {
  // x -> reflect_m(x) applied before the chain so far: the new mirror is
  // on the source's side of the others.
  const glm::dmat3 reflect = glm::dmat3(1.0) - 2.0 * glm::outerProduct(m.normal, m.normal);
  const vec3 shift = 2.0 * m.offset * m.normal;
  chain.shift = chain.linear * shift + chain.shift;
  chain.linear = chain.linear * reflect;
  chain.path.mirrors[std::size_t(chain.path.count++)] = index;
  chain.path.kr *= m.kr;
}

void set_window(mirror_chain& chain, const planar_mirror& m) {
  const vec3 n = m.normal;
  chain.u = glm::normalize(std::abs(n.x) > 0.9 ? glm::cross(n, vec3(0, 1, 0)) : glm::cross(n, vec3(1, 0, 0)));
  chain.v = glm::cross(n, chain.u);
  interval u, v;
  for (const vec3& c : m.corners) {
    u.add(glm::dot(chain.u, c));
    v.add(glm::dot(chain.v, c));
  }
  chain.u_lo = u.lo;
  chain.u_hi = u.hi;
  chain.v_lo = v.lo;
  chain.v_hi = v.hi;
}

// Two mirrors in one plane (the two sides of a two-sided mirror, or two
// panes side by side) never pass light to each other: what leaves the
// one goes away from the plane.
bool coplanar(const mirror_set& set, const planar_mirror& a, const planar_mirror& b) {
  const double same = glm::dot(a.normal, b.normal);
  return std::abs(std::abs(same) - 1.0) < 1e-9 &&
         std::abs(a.offset - (same > 0.0 ? b.offset : -b.offset)) <= set.tolerance;
}

void extend(const mirror_set& set, const mirror_chain& chain, int depth, std::vector<mirror_chain>& out) {
  if (chain.path.count >= depth) return;
  const int last = chain.path.count > 0 ? chain.path.mirrors[std::size_t(chain.path.count - 1)] : -1;
  for (int m = 0; m < int(set.mirrors.size()); ++m) {
    if (m == last || (last >= 0 && coplanar(set, set.mirrors[std::size_t(last)], set.mirrors[std::size_t(m)])))
      continue;
    mirror_chain next = chain;
    add_mirror(next, set.mirrors[std::size_t(m)], m);
    if (next.path.count == 1) set_window(next, set.mirrors[std::size_t(m)]);
    out.push_back(next);
    extend(set, next, depth, out);
  }
}

}  // namespace

std::vector<mirror_chain> mirror_chains(const mirror_set& mirrors, int depth) {
  std::vector<mirror_chain> out;
  extend(mirrors, mirror_chain{}, std::clamp(depth, 0, max_mirror_depth), out);
  return out;
}

void image_box(const mirror_chain& chain, const vec3& lo, const vec3& hi, vec3& image_lo, vec3& image_hi) {
  image_lo = vec3(INFINITY);
  image_hi = vec3(-INFINITY);
  for (const vec3& c : box_corners(lo, hi)) {
    const vec3 x = chain.image(c);
    image_lo = glm::min(image_lo, x);
    image_hi = glm::max(image_hi, x);
  }
}

bool box_reaches_in_front(const planar_mirror& mirror, const vec3& lo, const vec3& hi, double slack) {
  return along(box_corners(lo, hi), mirror.normal, mirror.offset).hi > slack;
}

bool may_cross_first_mirror(const mirror_set& mirrors, const mirror_chain& chain, const vec3& lo, const vec3& hi,
                            const vec3& image_lo, const vec3& image_hi) {
  const planar_mirror& m = mirrors.mirrors[std::size_t(chain.path.mirrors[0])];
  const std::array<vec3, 8> near = box_corners(lo, hi), far = box_corners(image_lo, image_hi);
  const double slack = mirrors.tolerance;
  // Heights above the plane: the receiver's side must reach in front, the
  // image's behind.
  interval h = along(near, m.normal, m.offset), g = along(far, -m.normal, -m.offset);
  if (!(h.hi > slack) || !(g.hi > slack)) return false;
  h.lo = std::max(h.lo, 0.0);
  g.lo = std::max(g.lo, 0.0);
  // A segment from p (height h) to q (depth g) crosses at p + w (q - p),
  // w = h / (h + g); the crossing's coordinate along an axis is bilinear
  // in (p, q) and monotone in w, so its extremes are at the corners.
  const double w_lo = h.lo + g.hi > 0.0 ? h.lo / (h.lo + g.hi) : 0.0;
  const double w_hi = h.hi / (h.hi + g.lo);
  auto crossing = [&](const vec3& axis) {
    const interval p = along(near, axis), q = along(far, axis);
    interval x;
    for (double a : {p.lo, p.hi})
      for (double b : {q.lo, q.hi})
        for (double w : {w_lo, w_hi}) x.add(a + w * (b - a));
    return x;
  };
  const interval x = crossing(chain.u), y = crossing(chain.v);
  return x.hi >= chain.u_lo - slack && x.lo <= chain.u_hi + slack && y.hi >= chain.v_lo - slack &&
         y.lo <= chain.v_hi + slack;
}

}  // namespace bounce
