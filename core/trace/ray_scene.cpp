#include "trace/ray_scene.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/embree_device.h"

#include "mesh/coplanar_cut.h"
#include "scene/framing.h"
#include "scene/scene_info.h"
#include "scene/tessellate.h"
#include "scene/texture.h"

namespace bounce {
namespace {

// Smallest root of a t^2 + b t + c = 0 in (t_min, t_max) that `accept`s,
// with the cancellation-free form of the quadratic formula.
template <typename predicate>
std::optional<double> first_root(double a, double b, double c, double t_min, double t_max, predicate&& accept) {
  double roots[2];
  int count = 0;
  if (std::abs(a) < 1e-300) {  // degenerate: linear along this ray
    if (b == 0.0) return std::nullopt;
    roots[count++] = -c / b;
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return std::nullopt;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    roots[count++] = q / a;
    if (q != 0.0) roots[count++] = c / q;
    if (count == 2 && roots[1] < roots[0]) std::swap(roots[0], roots[1]);
  }
  for (int i = 0; i < count; ++i)
    if (roots[i] > t_min && roots[i] < t_max && accept(roots[i])) return roots[i];
  return std::nullopt;
}

struct analytic_shape {
  bool is_sphere = true;
  sphere ball;
  quadric q;
  int surface = 0;

  std::optional<double> hit(const vec3& o, const vec3& d, double t_min, double t_max) const {
    if (is_sphere) {
      const vec3 oc = o - ball.center;
      return first_root(glm::dot(d, d), 2.0 * glm::dot(oc, d), glm::dot(oc, oc) - ball.radius * ball.radius, t_min,
                        t_max, [](double) { return true; });
    }
    // f(o + t d) = A t^2 + B t + C, from f(p) = p'Qp + 2 l.p + k.
    const glm::dmat3 Q(q.a, q.d, q.f, q.d, q.b, q.e, q.f, q.e, q.c);
    const vec3 l(q.g, q.h, q.j);
    const double a = glm::dot(d, Q * d);
    const double b = 2.0 * (glm::dot(d, Q * o) + glm::dot(l, d));
    const double c = quadric_value(q, o);
    // Only the part of the surface inside its box counts (a small margin
    // for the points computed on the box's faces).
    const vec3 margin = 1e-12 * (q.box_max - q.box_min);
    return first_root(a, b, c, t_min, t_max, [&](double t) {
      const vec3 p = o + t * d;
      return glm::all(glm::greaterThanEqual(p, q.box_min - margin)) &&
             glm::all(glm::lessThanEqual(p, q.box_max + margin));
    });
  }

  vec3 gradient(const vec3& p) const { return is_sphere ? p - ball.center : quadric_gradient(q, p); }
  vec3 normal(const vec3& p) const { return glm::normalize(gradient(p)); }

  // Spheres: longitude and latitude, v = 1 at the top (+y), where an
  // image's top row goes. Quadrics have no natural parameters: cylindrical
  // ones about the box's vertical axis (angle, height in the box).
  vec2 uv(const vec3& p) const {
    constexpr double two_pi = 2.0 * std::numbers::pi;
    if (is_sphere) {
      const vec3 n = glm::normalize(p - ball.center);
      return {std::atan2(n.z, n.x) / two_pi + 0.5, 1.0 - std::acos(std::clamp(n.y, -1.0, 1.0)) / std::numbers::pi};
    }
    const vec3 centre = 0.5 * (q.box_min + q.box_max);
    const double height = q.box_max.y - q.box_min.y;
    return {std::atan2(p.z - centre.z, p.x - centre.x) / two_pi + 0.5, height > 0 ? (p.y - q.box_min.y) / height : 0.0};
  }
};

void analytic_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* shape = static_cast<const analytic_shape*>(args->geometryUserPtr);
  const vec3 lo = shape->is_sphere ? shape->ball.center - vec3(shape->ball.radius) : shape->q.box_min;
  const vec3 hi = shape->is_sphere ? shape->ball.center + vec3(shape->ball.radius) : shape->q.box_max;
  // Rounded outwards to floats.
  args->bounds_o->lower_x = std::nextafter(float(lo.x), -INFINITY);
  args->bounds_o->lower_y = std::nextafter(float(lo.y), -INFINITY);
  args->bounds_o->lower_z = std::nextafter(float(lo.z), -INFINITY);
  args->bounds_o->upper_x = std::nextafter(float(hi.x), INFINITY);
  args->bounds_o->upper_y = std::nextafter(float(hi.y), INFINITY);
  args->bounds_o->upper_z = std::nextafter(float(hi.z), INFINITY);
}

// The closest-hit queries' context: Embree's, followed by the caller's
// rays in double (indexed by the rays' id), so that spheres and quadrics
// are intersected with the exact ray once, in the callback, and the root
// found there is the hit's t (Embree passes the context's address through
// to the callbacks; RTCIntersectContext must come first).
struct double_rays_context {
  RTCIntersectContext embree;
  const vec3* origins = nullptr;  // nullptr: the callbacks use Embree's float rays
  const vec3* directions = nullptr;
  double t_min = 0.0, t_max = INFINITY;
  // Per ray id: the analytic geometry whose hit was accepted last (the
  // closest so far: Embree only offers hits nearer than the current one)
  // and its exact t.
  unsigned geom_id[16];
  double t[16];

  double_rays_context() {
    rtcInitIntersectContext(&embree);
    std::fill(std::begin(geom_id), std::end(geom_id), RTC_INVALID_GEOMETRY_ID);
  }
};
static_assert(offsetof(double_rays_context, embree) == 0);

void analytic_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* shape = static_cast<const analytic_shape*>(args->geometryUserPtr);
  auto* context = reinterpret_cast<double_rays_context*>(args->context);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned id = RTCRayN_id(rays, args->N, i);
    const bool exact = context->origins != nullptr;
    const vec3 o =
        exact ? context->origins[id]
              : vec3(RTCRayN_org_x(rays, args->N, i), RTCRayN_org_y(rays, args->N, i), RTCRayN_org_z(rays, args->N, i));
    const vec3 d =
        exact ? context->directions[id]
              : vec3(RTCRayN_dir_x(rays, args->N, i), RTCRayN_dir_y(rays, args->N, i), RTCRayN_dir_z(rays, args->N, i));
    const double far = RTCRayN_tfar(rays, args->N, i);
    const auto t = exact ? shape->hit(o, d, context->t_min, std::min(context->t_max, far))
                         : shape->hit(o, d, RTCRayN_tnear(rays, args->N, i), far);
    if (!t) continue;
    if (exact) {
      context->geom_id[id] = args->geomID;
      context->t[id] = *t;
    }
    const vec3 n = shape->gradient(o + *t * d);  // Embree's Ng need not be unit length (nothing here reads it)
    RTCRayN_tfar(rays, args->N, i) = float(*t);
    RTCHitN_Ng_x(hits, args->N, i) = float(n.x);
    RTCHitN_Ng_y(hits, args->N, i) = float(n.y);
    RTCHitN_Ng_z(hits, args->N, i) = float(n.z);
    RTCHitN_u(hits, args->N, i) = 0.0f;
    RTCHitN_v(hits, args->N, i) = 0.0f;
    RTCHitN_primID(hits, args->N, i) = args->primID;
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
  }
}

void analytic_occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* shape = static_cast<const analytic_shape*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const vec3 o(RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                 RTCRayN_org_z(args->ray, args->N, i));
    const vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                 RTCRayN_dir_z(args->ray, args->N, i));
    if (shape->hit(o, d, RTCRayN_tnear(args->ray, args->N, i), RTCRayN_tfar(args->ray, args->N, i)))
      RTCRayN_tfar(args->ray, args->N, i) = -INFINITY;
  }
}

// A triangle mesh with cut-out materials (material::alpha_cutoff): hits in
// their holes are rejected, for camera, bounce and shadow rays alike.
// Copies: the ray scene may outlive the scene it was built from.
// The scene's materials and the textures of its cut-out ones (the rest
// left empty), shared by every cut-out mesh.
struct cut_out_tables {
  std::vector<material> materials;
  std::vector<texture> textures;
};

struct cut_out_mesh {
  std::vector<glm::ivec3> triangles;
  std::vector<vec2> uvs;
  std::vector<int> materials;
  std::shared_ptr<const cut_out_tables> tables;
};

void reject_holes(const RTCFilterFunctionNArguments* args) {
  const auto* mesh = static_cast<const cut_out_mesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const double u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const glm::ivec3 t = mesh->triangles[prim];
    const vec2 uv = (1 - u - v) * mesh->uvs[std::size_t(t[0])] + u * mesh->uvs[std::size_t(t[1])] +
                    v * mesh->uvs[std::size_t(t[2])];
    if (cut_out(mesh->tables->materials[std::size_t(mesh->materials[prim])], mesh->tables->textures, uv))
      args->valid[i] = 0;
  }
}

}  // namespace

// Per Embree geometry: either a triangle mesh (with what shading needs) or
// an analytic shape.
struct ray_scene::embree_state {
  RTCScene scene = nullptr;
  struct geometry {
    int surface = -1;
    triangle_mesh triangles;                // empty for analytic shapes
    std::unique_ptr<analytic_shape> shape;  // stable address: Embree keeps a pointer
    std::unique_ptr<cut_out_mesh> holes;    // the same, when some of its materials cut out
  };
  std::vector<geometry> geometries;  // indexed by Embree geomID

  struct emitter {
    bool is_sphere = false;
    vec3 p0{0.0}, p1{0.0}, p2{0.0};  // triangle corners, or the sphere's centre in p0
    double radius = 0.0;
    rgb radiance{0.0};
    int surface = -1;
  };
  std::vector<emitter> emitters;
  std::vector<double> emitter_cdf;  // running sum of the emitters' areas
  std::vector<bool> sampled_surfaces;

  void add_emitters(const bounce::scene& s, const geometry& g);
  // The hit Embree found (in floats), recomputed in double from the
  // caller's double ray.
  // `context` holds the exact t of analytic hits, from the callback.
  ray_hit hit_of(unsigned geom_id, unsigned prim_id, float u, float v, float t_float, const vec3& origin,
                 const vec3& direction, double t_min, double t_max, const double_rays_context& context,
                 unsigned ray_id) const;
};

ray_scene::ray_scene(const scene& s, double patch_edge) : state_(std::make_unique<embree_state>()) {
  const bounds3 b = scene_bounds(s);
  offset_ = 1e-5 * std::max(glm::length(b.max - b.min), 1e-300);
  RTCDevice dev = embree_device();
  state_->scene = rtcNewScene(dev);
  rtcSetSceneFlags(state_->scene, RTC_SCENE_FLAG_ROBUST);
  // Triangulated surfaces first, with coplanar overlaps cut out of the
  // surface behind exactly as the patch mesher does (coplanar_cut.h): a
  // light in the ceiling's plane would otherwise leave two coincident
  // surfaces, and which one a ray hits would depend on Embree's traversal.
  std::vector<triangle_mesh> tessellated(s.surfaces.size());
  std::vector<bool> flat(s.surfaces.size(), false);
  const double edge = patch_edge > 0.0 ? patch_edge : 0.25 * default_max_edge(s);
  for (std::size_t i = 0; i < s.surfaces.size(); ++i) {
    const shape& geometry = s.surfaces[i].geometry;
    if (std::holds_alternative<sphere>(geometry) || std::holds_alternative<quadric>(geometry)) continue;
    tessellated[i] = tessellate(s.surfaces[i], edge);
    flat[i] = std::holds_alternative<polygon_mesh>(geometry);
  }
  cut_coplanar_overlaps(tessellated, flat, s.materials, glm::length(b.max - b.min));
  std::shared_ptr<const cut_out_tables> cut_tables;  // made by the first cut-out mesh
  for (std::size_t i = 0; i < s.surfaces.size(); ++i) {
    const surface& surf = s.surfaces[i];
    embree_state::geometry g;
    g.surface = int(i);
    RTCGeometry geometry = nullptr;
    if (const auto* b = std::get_if<sphere>(&surf.geometry)) {
      g.shape = std::make_unique<analytic_shape>(analytic_shape{true, *b, {}, int(i)});
    } else if (const auto* q = std::get_if<quadric>(&surf.geometry)) {
      g.shape = std::make_unique<analytic_shape>(analytic_shape{false, {}, *q, int(i)});
    }
    if (g.shape) {
      geometry = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geometry, 1);
      rtcSetGeometryUserData(geometry, g.shape.get());
      rtcSetGeometryBoundsFunction(geometry, analytic_bounds, nullptr);
      rtcSetGeometryIntersectFunction(geometry, analytic_intersect);
      rtcSetGeometryOccludedFunction(geometry, analytic_occluded);
    } else {
      g.triangles = std::move(tessellated[i]);
      if (g.triangles.triangles.empty()) continue;
      geometry = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), g.triangles.positions.size()));
      for (std::size_t k = 0; k < g.triangles.positions.size(); ++k)
        for (int c = 0; c < 3; ++c) v[3 * k + c] = float(g.triangles.positions[k][c]);
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), g.triangles.triangles.size()));
      for (std::size_t k = 0; k < g.triangles.triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) idx[3 * k + c] = unsigned(g.triangles.triangles[k][c]);
      const bool cuts = std::any_of(g.triangles.materials.begin(), g.triangles.materials.end(),
                                    [&](int m) { return s.materials[std::size_t(m)].alpha_cutoff > 0.0; });
      if (cuts && g.triangles.uvs.size() == g.triangles.positions.size()) {
        g.holes = std::make_unique<cut_out_mesh>();
        g.holes->triangles = g.triangles.triangles;
        g.holes->uvs = g.triangles.uvs;
        g.holes->materials = g.triangles.materials;
        if (!cut_tables) {
          auto tables = std::make_shared<cut_out_tables>();
          tables->materials = s.materials;
          tables->textures.resize(s.textures.size());
          for (const material& m : s.materials)
            if (m.alpha_cutoff > 0.0 && m.texture >= 0 && std::size_t(m.texture) < s.textures.size())
              tables->textures[std::size_t(m.texture)] = s.textures[std::size_t(m.texture)];
          cut_tables = std::move(tables);
        }
        g.holes->tables = cut_tables;
        rtcSetGeometryUserData(geometry, g.holes.get());
        rtcSetGeometryIntersectFilterFunction(geometry, reject_holes);
        rtcSetGeometryOccludedFilterFunction(geometry, reject_holes);
      }
    }
    state_->add_emitters(s, g);
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(state_->scene, geometry);
    rtcReleaseGeometry(geometry);
    if (state_->geometries.size() <= id) state_->geometries.resize(id + 1);
    state_->geometries[id] = std::move(g);
  }
  rtcCommitScene(state_->scene);
  double area = 0.0;
  for (const embree_state::emitter& e : state_->emitters) {
    area += e.is_sphere ? 4.0 * std::numbers::pi * e.radius * e.radius
                        : 0.5 * glm::length(glm::cross(e.p1 - e.p0, e.p2 - e.p0));
    state_->emitter_cdf.push_back(area);
  }
}

void ray_scene::embree_state::add_emitters(const bounce::scene& s, const geometry& g) {
  auto emitting = [&](int material) { return any_positive(s.materials[material].ke); };
  if (g.shape) {
    if (!g.shape->is_sphere || !emitting(g.shape->ball.material)) return;
    emitter e;
    e.is_sphere = true;
    e.p0 = g.shape->ball.center;
    e.radius = g.shape->ball.radius;
    e.radiance = s.materials[g.shape->ball.material].ke;
    e.surface = g.surface;
    emitters.push_back(e);
  } else {
    const triangle_mesh& m = g.triangles;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      if (!emitting(m.materials[t])) continue;
      emitter e;
      e.p0 = m.positions[m.triangles[t][0]];
      e.p1 = m.positions[m.triangles[t][1]];
      e.p2 = m.positions[m.triangles[t][2]];
      e.radiance = s.materials[m.materials[t]].ke;
      e.surface = g.surface;
      emitters.push_back(e);
    }
  }
  if (!emitters.empty() && emitters.back().surface == g.surface) {
    if (sampled_surfaces.size() <= std::size_t(g.surface)) sampled_surfaces.resize(g.surface + 1, false);
    sampled_surfaces[g.surface] = true;
  }
}

double ray_scene::emitter_area() const {
  return state_->emitter_cdf.empty() ? 0.0 : state_->emitter_cdf.back();
}

bool ray_scene::is_sampled_emitter(int surface) const {
  const std::vector<bool>& sampled = state_->sampled_surfaces;
  return surface >= 0 && std::size_t(surface) < sampled.size() && sampled[surface];
}

emitter_sample ray_scene::sample_emitter(double u1, double u2) const {
  emitter_sample out;
  const auto& emitters = state_->emitters;
  const auto& cdf = state_->emitter_cdf;
  if (emitters.empty()) return out;
  // Pick the emitter by area with u1, then reuse u1's position inside its
  // slice of the CDF, so stratification in u1 carries over.
  const double total = cdf.back();
  const double target = u1 * total;
  const std::size_t i =
      std::min<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin(), emitters.size() - 1);
  const double lo = i ? cdf[i - 1] : 0.0;
  const double u = std::clamp((target - lo) / std::max(cdf[i] - lo, 1e-300), 0.0, 1.0 - 1e-16);
  const embree_state::emitter& e = emitters[i];
  if (e.is_sphere) {
    const double z = 1.0 - 2.0 * u, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * std::numbers::pi * u2;
    out.normal = vec3(r * std::cos(phi), r * std::sin(phi), z);
    out.point = e.p0 + e.radius * out.normal;
  } else {
    const double su = std::sqrt(u);
    out.point = (1.0 - su) * e.p0 + su * (1.0 - u2) * e.p1 + su * u2 * e.p2;
    out.normal = glm::normalize(glm::cross(e.p1 - e.p0, e.p2 - e.p0));
  }
  out.radiance = e.radiance;
  out.pdf_area = 1.0 / total;
  return out;
}

ray_scene::~ray_scene() {
  if (state_ && state_->scene) rtcReleaseScene(state_->scene);
}

std::optional<ray_hit> ray_scene::intersect(const vec3& origin, const vec3& direction, double t_min,
                                            double t_max) const {
  double_rays_context context;
  context.origins = &origin;
  context.directions = &direction;
  context.t_min = t_min;
  context.t_max = t_max;
  RTCRayHit rh{};
  rh.ray.org_x = float(origin.x);
  rh.ray.org_y = float(origin.y);
  rh.ray.org_z = float(origin.z);
  rh.ray.dir_x = float(direction.x);
  rh.ray.dir_y = float(direction.y);
  rh.ray.dir_z = float(direction.z);
  rh.ray.tnear = float(t_min);
  rh.ray.tfar = std::isinf(t_max) ? INFINITY : float(t_max);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(state_->scene, &context.embree, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return state_->hit_of(rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, origin, direction, t_min, t_max,
                        context, 0);
}

ray_hit ray_scene::embree_state::hit_of(unsigned geom_id, unsigned prim_id, float u_float, float v_float, float t_float,
                                        const vec3& origin, const vec3& direction, double t_min, double t_max,
                                        const double_rays_context& context, unsigned ray_id) const {
  // Embree chose the closest surface in floats; the hit itself is
  // recomputed in double from the caller's double ray.
  const geometry& g = geometries[geom_id];
  ray_hit hit;
  hit.surface = g.surface;
  if (g.shape) {
    if (context.origins && context.geom_id[ray_id] == geom_id) {
      hit.t = context.t[ray_id];  // the callback's root, on this very ray
    } else {
      // The exact root nearest the float one (Embree's t is accurate to
      // float precision; widen its window by a relative 1e-5).
      auto t = g.shape->hit(origin, direction, std::max(t_min, t_float * (1 - 1e-5) - 1e-300),
                            std::min(t_max, t_float * (1 + 1e-5) + 1e-300));
      hit.t = t ? *t : t_float;
    }
    hit.point = origin + hit.t * direction;
    hit.normal = g.shape->normal(hit.point);
    hit.face_normal = hit.normal;
    hit.uv = g.shape->uv(hit.point);
    hit.material = g.shape->is_sphere ? g.shape->ball.material : g.shape->q.material;
    return hit;
  }
  const triangle_mesh& m = g.triangles;
  const glm::ivec3 tri = m.triangles[prim_id];
  const vec3 p0 = m.positions[tri[0]], p1 = m.positions[tri[1]], p2 = m.positions[tri[2]];
  const vec3 face = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  hit.t = glm::dot(face, p0 - origin) / glm::dot(face, direction);  // the plane, in double
  hit.point = origin + hit.t * direction;
  const double u = u_float, v = v_float;
  const vec3 shading = (1 - u - v) * m.normals[tri[0]] + u * m.normals[tri[1]] + v * m.normals[tri[2]];
  hit.normal = glm::length(shading) > 0 ? glm::normalize(shading) : face;
  hit.face_normal = face;
  hit.uv = (1 - u - v) * m.uvs[tri[0]] + u * m.uvs[tri[1]] + v * m.uvs[tri[2]];
  hit.material = m.materials[prim_id];
  return hit;
}

void ray_scene::intersect_packets(std::span<const vec3> origins, std::span<const vec3> directions,
                                  std::span<std::optional<ray_hit>> hits, double t_min, double t_max) const {
  if (origins.size() != directions.size() || origins.size() != hits.size())
    throw std::invalid_argument("ray_scene::intersect_packets: " + std::to_string(origins.size()) + " origins, " +
                                std::to_string(directions.size()) + " directions and " + std::to_string(hits.size()) +
                                " hits");
  const float near = float(t_min), far = std::isinf(t_max) ? INFINITY : float(t_max);
  for (std::size_t begin = 0; begin < origins.size(); begin += 8) {
    const std::size_t count = std::min<std::size_t>(8, origins.size() - begin);
    double_rays_context context;  // ray id i is origins[begin + i]
    context.origins = origins.data() + begin;
    context.directions = directions.data() + begin;
    context.t_min = t_min;
    context.t_max = t_max;
    alignas(32) int valid[8];
    RTCRayHit8 rh;  // aligned by its type
    for (std::size_t i = 0; i < 8; ++i) {
      // Lanes past the end are switched off, and hold the last ray so
      // that nothing Embree reads is garbage.
      valid[i] = i < count ? -1 : 0;
      const std::size_t k = begin + std::min(i, count - 1);
      rh.ray.org_x[i] = float(origins[k].x);
      rh.ray.org_y[i] = float(origins[k].y);
      rh.ray.org_z[i] = float(origins[k].z);
      rh.ray.dir_x[i] = float(directions[k].x);
      rh.ray.dir_y[i] = float(directions[k].y);
      rh.ray.dir_z[i] = float(directions[k].z);
      rh.ray.tnear[i] = near;
      rh.ray.tfar[i] = far;
      rh.ray.time[i] = 0.0f;
      rh.ray.mask[i] = 0xFFFFFFFFu;
      rh.ray.id[i] = unsigned(k - begin);  // which of the context's double rays
      rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, state_->scene, &context.embree, &rh);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t k = begin + i;
      if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID)
        hits[k].reset();
      else
        hits[k] = state_->hit_of(rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], rh.ray.tfar[i],
                                 origins[k], directions[k], t_min, t_max, context, unsigned(i));
    }
  }
}

namespace {

// Embree's closest hits of `rays` in packets of K (rayhit_k: RTCRayHit4,
// 8 or 16), as a renderer using Embree directly would cast them.
template <int K, typename rayhit_k>
std::size_t closest_hits_k(RTCScene scene, std::span<const float_ray> rays, float* t_hit,
                           void (*intersect_k)(const int*, RTCScene, RTCIntersectContext*, rayhit_k*)) {
  double_rays_context context;  // no double rays: the callbacks use Embree's float ones
  std::size_t hit_count = 0;
  for (std::size_t begin = 0; begin < rays.size(); begin += K) {
    const std::size_t count = std::min<std::size_t>(K, rays.size() - begin);
    alignas(4 * K) int valid[K];
    rayhit_k rh;  // aligned by its type
    for (std::size_t i = 0; i < std::size_t(K); ++i) {
      valid[i] = i < count ? -1 : 0;
      const float_ray& r = rays[begin + std::min(i, count - 1)];
      rh.ray.org_x[i] = r.origin[0];
      rh.ray.org_y[i] = r.origin[1];
      rh.ray.org_z[i] = r.origin[2];
      rh.ray.dir_x[i] = r.direction[0];
      rh.ray.dir_y[i] = r.direction[1];
      rh.ray.dir_z[i] = r.direction[2];
      rh.ray.tnear[i] = r.t_min;
      rh.ray.tfar[i] = r.t_max;
      rh.ray.time[i] = 0.0f;
      rh.ray.mask[i] = 0xFFFFFFFFu;
      rh.ray.id[i] = unsigned(i);
      rh.ray.flags[i] = 0;
      rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    intersect_k(valid, scene, &context.embree, &rh);
    for (std::size_t i = 0; i < count; ++i) {
      const bool hit = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
      hit_count += hit;
      if (t_hit) t_hit[begin + i] = hit ? rh.ray.tfar[i] : INFINITY;
    }
  }
  return hit_count;
}

}  // namespace

std::size_t ray_scene::embree_closest_hits(std::span<const float_ray> rays, int width, float* t_hit) const {
  switch (width) {
    case 4:
      return closest_hits_k<4>(state_->scene, rays, t_hit, rtcIntersect4);
    case 8:
      return closest_hits_k<8>(state_->scene, rays, t_hit, rtcIntersect8);
    case 16:
      return closest_hits_k<16>(state_->scene, rays, t_hit, rtcIntersect16);
    case 1:
      break;
    default:
      throw std::invalid_argument("ray_scene::embree_closest_hits: packets of " + std::to_string(width) +
                                  " (expected 1, 4, 8 or 16)");
  }
  double_rays_context context;  // no double rays: the callbacks use Embree's float ones
  std::size_t hit_count = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    const float_ray& r = rays[k];
    RTCRayHit rh{};
    rh.ray.org_x = r.origin[0];
    rh.ray.org_y = r.origin[1];
    rh.ray.org_z = r.origin[2];
    rh.ray.dir_x = r.direction[0];
    rh.ray.dir_y = r.direction[1];
    rh.ray.dir_z = r.direction[2];
    rh.ray.tnear = r.t_min;
    rh.ray.tfar = r.t_max;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(state_->scene, &context.embree, &rh);
    const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    hit_count += hit;
    if (t_hit) t_hit[k] = hit ? rh.ray.tfar : INFINITY;
  }
  return hit_count;
}

bool ray_scene::native_packet(int width) {
  const RTCDeviceProperty property = width == 4    ? RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED
                                     : width == 8  ? RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED
                                     : width == 16 ? RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED
                                                   : RTC_DEVICE_PROPERTY_VERSION;
  if (property == RTC_DEVICE_PROPERTY_VERSION) return false;
  return rtcGetDeviceProperty(embree_device(), property) != 0;
}

bool ray_scene::occluded(const vec3& from, const vec3& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  const vec3 d = to - from;
  ray.org_x = float(from.x);
  ray.org_y = float(from.y);
  ray.org_z = float(from.z);
  ray.dir_x = float(d.x);
  ray.dir_y = float(d.y);
  ray.dir_z = float(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;
  ray.mask = 0xFFFFFFFFu;
  rtcOccluded1(state_->scene, &context, &ray);
  return ray.tfar < 0.0f;
}

}  // namespace bounce
