#include "trace/radiosity_field.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "base/embree_device.h"

namespace bounce {
namespace {

// Closest point of triangle abc to p (Ericson, Real-Time Collision
// Detection 5.1.5), as barycentric weights.
vec3 closest_barycentric(const vec3& p, const vec3& a, const vec3& b, const vec3& c) {
  const vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const vec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const vec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

struct query {
  const patch_mesh* mesh;
  const std::vector<int>* element_of;  // per Embree geometry: its surface's element list
  unsigned geometry;                   // the surface's Embree geometry
  vec3 point;
  double best_distance2 = std::numeric_limits<double>::infinity();
  int element = -1;
  vec3 weights{0.0};
};

// A probe ray's context: Embree's, followed by the one surface (Embree
// geometry) whose elements the probe may hit (RTCIntersectContext must
// come first: Embree passes the context's address to the filter).
struct probe_context {
  RTCIntersectContext embree;
  unsigned geometry;
};
static_assert(offsetof(probe_context, embree) == 0);

// Rejects the probe's hits on other surfaces (a wall's neighbour at a
// corner).
void same_surface_only(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const probe_context*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] != 0 && RTCHitN_geomID(args->hit, args->N, i) != context->geometry) args->valid[i] = 0;
}

}  // namespace

struct radiosity_field::embree_state {
  RTCScene scene = nullptr;
  std::vector<unsigned> geometry_of_surface;  // Embree geometry per scene surface (or invalid)
  std::vector<std::vector<int>> elements_of;  // per Embree geometry: mesh element per primitive
  ~embree_state() {
    if (scene) rtcReleaseScene(scene);
  }
};

namespace {

bool closest_element(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<query*>(args->userPtr);
  if (args->geomID != q->geometry) return false;
  const int e = q->element_of[args->geomID][args->primID];
  const auto [a, b, c] = element_corners(*q->mesh, std::size_t(e));
  const vec3 w = closest_barycentric(q->point, a, b, c);
  const vec3 closest = w.x * a + w.y * b + w.z * c;
  const double d2 = glm::dot(closest - q->point, closest - q->point);
  if (d2 >= q->best_distance2) return false;
  q->best_distance2 = d2;
  q->element = e;
  q->weights = w;
  // Shrink the search (never grow it: Embree's rule); float, rounded up.
  const float radius = std::nextafter(float(std::sqrt(d2)), INFINITY);
  if (radius < args->query->radius) {
    args->query->radius = radius;
    return true;
  }
  return false;
}

}  // namespace

radiosity_field::radiosity_field(const patch_mesh& mesh, std::span<const rgb> radiosity, std::span<const rgb> direct,
                                 const rgb& ambient, std::span<const rgb> caustic)
    : mesh_(mesh), state_(std::make_unique<embree_state>()) {
  vertex_values_.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const rgb unshot = mesh.vertex_rho[v] * ambient;  // indirect light by definition
    const rgb reflected = radiosity[v] - mesh.vertex_emission[v] + unshot;
    // B >= E + direct holds by the solvers' construction; subtracting two
    // sums can leave a round-off of -1e-17, which is not light taken away.
    vertex_values_[v] = {reflected, direct.empty() ? reflected : glm::max(reflected - direct[v], rgb(0.0)),
                         caustic.empty() ? rgb(0.0) : caustic[v]};
  }

  int surfaces = 0;
  for (int s : mesh.element_surfaces) surfaces = std::max(surfaces, s + 1);
  std::vector<std::vector<int>> by_surface(surfaces);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) by_surface[mesh.element_surfaces[e]].push_back(int(e));

  RTCDevice dev = embree_device();
  state_->scene = rtcNewScene(dev);
  state_->geometry_of_surface.assign(surfaces, RTC_INVALID_GEOMETRY_ID);
  for (int s = 0; s < surfaces; ++s) {
    if (by_surface[s].empty()) continue;
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::vector<int>& elements = by_surface[s];
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), 3 * elements.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), elements.size()));
    for (std::size_t i = 0; i < elements.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const vec3 p = mesh.positions[mesh.elements[elements[i]][k]];
        for (int c = 0; c < 3; ++c) v[9 * i + 3 * k + c] = float(p[c]);
        idx[3 * i + k] = unsigned(3 * i + k);
      }
    rtcSetGeometryIntersectFilterFunction(g, same_surface_only);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(state_->scene, g);
    rtcReleaseGeometry(g);
    if (state_->elements_of.size() <= id) state_->elements_of.resize(id + 1);
    state_->elements_of[id] = elements;
    state_->geometry_of_surface[s] = id;
  }
  rtcCommitScene(state_->scene);
}

radiosity_field::~radiosity_field() = default;

diffuse_radiosity radiosity_field::at(int surface, const vec3& point, const vec3& normal) const {
  if (surface < 0 || std::size_t(surface) >= state_->geometry_of_surface.size() ||
      state_->geometry_of_surface[surface] == RTC_INVALID_GEOMETRY_ID)
    return {};
  const unsigned geometry = state_->geometry_of_surface[surface];
  int element = -1;
  vec3 weights(0.0);
  // First a short probe ray along the normal through the point: on a flat
  // surface it hits the element that holds the point, with its
  // barycentric weights, at the cost of one ray (a closest-point query
  // visits every element within its radius). The probe reaches as far as
  // the tessellation's chord error on curved surfaces (an element's size
  // bounds it).
  const double reach = std::max(mesh_.max_edge, 1e-6 * mesh_.scene_diagonal);
  const vec3 n = glm::normalize(normal);
  const vec3 start = point + reach * n;
  RTCRayHit probe;
  probe.ray.org_x = float(start.x);
  probe.ray.org_y = float(start.y);
  probe.ray.org_z = float(start.z);
  probe.ray.dir_x = float(-n.x);
  probe.ray.dir_y = float(-n.y);
  probe.ray.dir_z = float(-n.z);
  probe.ray.tnear = 0.0f;
  probe.ray.tfar = float(2.0 * reach);
  probe.ray.time = 0.0f;
  probe.ray.mask = ~0u;
  probe.ray.id = 0;
  probe.ray.flags = 0;
  probe.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  probe_context context;
  rtcInitIntersectContext(&context.embree);
  context.geometry = geometry;
  rtcIntersect1(state_->scene, &context.embree, &probe);
  if (probe.hit.geomID == geometry) {
    element = state_->elements_of[geometry][probe.hit.primID];
    weights = vec3(1.0 - probe.hit.u - probe.hit.v, probe.hit.u, probe.hit.v);
  } else {
    // Off the tessellation (past its boundary, or in a crack): the
    // nearest element of the surface.
    query q{&mesh_, state_->elements_of.data(), geometry, point};
    RTCPointQuery pq;
    pq.x = float(point.x);
    pq.y = float(point.y);
    pq.z = float(point.z);
    pq.time = 0.0f;
    pq.radius = float(2.0 * reach);
    RTCPointQueryContext point_context;
    rtcInitPointQueryContext(&point_context);
    rtcPointQuery(state_->scene, &pq, &point_context, closest_element, &q);
    if (q.element < 0) return {};
    element = q.element;
    weights = q.weights;
  }
  const glm::ivec3 t = mesh_.elements[element];
  diffuse_radiosity out;
  for (int k = 0; k < 3; ++k) {
    out.reflected += weights[k] * vertex_values_[t[k]].reflected;
    out.indirect += weights[k] * vertex_values_[t[k]].indirect;
    out.caustic += weights[k] * vertex_values_[t[k]].caustic;
  }
  return out;
}

}  // namespace bounce
