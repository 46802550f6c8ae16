#include "radiosity/transfer/occlusion.h"

#include <atomic>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "base/embree_device.h"

namespace bounce {

struct occlusion_scene::embree_state {
  RTCScene scene = nullptr;
  std::vector<segment> recorded;               // sized once by record_segments
  std::atomic<std::size_t> recorded_count{0};  // slots claimed so far
};

occlusion_scene::occlusion_scene(std::span<const vec3> positions, std::span<const glm::ivec3> triangles)
    : state_(std::make_unique<embree_state>()) {
  RTCDevice device = embree_device();
  state_->scene = rtcNewScene(device);
  rtcSetSceneFlags(state_->scene, RTC_SCENE_FLAG_ROBUST);  // no cracks between shared edges
  if (!triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + k] = static_cast<float>(positions[i][k]);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), triangles.size()));
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = static_cast<unsigned>(triangles[i][k]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(state_->scene, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(state_->scene);
}

occlusion_scene::~occlusion_scene() {
  if (state_ && state_->scene) rtcReleaseScene(state_->scene);
}

bool occlusion_scene::occluded(const vec3& from, const vec3& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  const vec3 d = to - from;
  ray.org_x = static_cast<float>(from.x);
  ray.org_y = static_cast<float>(from.y);
  ray.org_z = static_cast<float>(from.z);
  ray.dir_x = static_cast<float>(d.x);
  ray.dir_y = static_cast<float>(d.y);
  ray.dir_z = static_cast<float>(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;  // the segment, in units of d
  ray.mask = 0xFFFFFFFFu;
  rtcOccluded1(state_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

occlusion_scene::crossing occlusion_scene::first_crossing(const vec3& from, const vec3& to) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit query{};
  const vec3 d = to - from;
  query.ray.org_x = static_cast<float>(from.x);
  query.ray.org_y = static_cast<float>(from.y);
  query.ray.org_z = static_cast<float>(from.z);
  query.ray.dir_x = static_cast<float>(d.x);
  query.ray.dir_y = static_cast<float>(d.y);
  query.ray.dir_z = static_cast<float>(d.z);
  query.ray.tnear = 0.0f;
  query.ray.tfar = 1.0f;
  query.ray.mask = 0xFFFFFFFFu;
  query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  query.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(state_->scene, &context, &query);
  crossing out;
  if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
  out.triangle = static_cast<int>(query.hit.primID);
  out.t = query.ray.tfar;
  out.u = query.hit.u;
  out.v = query.hit.v;
  return out;
}

void occlusion_scene::record_segments(std::size_t capacity) {
  state_->recorded.assign(capacity, segment{});
  state_->recorded_count = 0;
}

std::vector<occlusion_scene::segment> occlusion_scene::recorded_segments() const {
  const std::size_t n = std::min(state_->recorded_count.load(), state_->recorded.size());
  return {state_->recorded.begin(), state_->recorded.begin() + std::ptrdiff_t(n)};
}

int occlusion_scene::count_unblocked(const vec3& from, std::span<const vec3> targets) const {
  if (state_->recorded_count.load(std::memory_order_relaxed) < state_->recorded.size()) {
    const std::size_t slot = state_->recorded_count.fetch_add(targets.size());
    for (std::size_t i = 0; i < targets.size() && slot + i < state_->recorded.size(); ++i)
      state_->recorded[slot + i] = {from, targets[i]};
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // rays share their origin
  int unblocked = 0;
  for (std::size_t start = 0; start < targets.size(); start += 8) {
    alignas(32) RTCRay8 rays;
    alignas(32) int valid[8];
    for (int i = 0; i < 8; ++i) {
      const std::size_t t = start + i;
      valid[i] = t < targets.size() ? -1 : 0;
      const vec3 d = t < targets.size() ? targets[t] - from : vec3(0, 0, 1);
      rays.org_x[i] = static_cast<float>(from.x);
      rays.org_y[i] = static_cast<float>(from.y);
      rays.org_z[i] = static_cast<float>(from.z);
      rays.dir_x[i] = static_cast<float>(d.x);
      rays.dir_y[i] = static_cast<float>(d.y);
      rays.dir_z[i] = static_cast<float>(d.z);
      rays.tnear[i] = 0.0f;
      rays.tfar[i] = 1.0f;
      rays.time[i] = 0.0f;
      rays.mask[i] = 0xFFFFFFFFu;
      rays.id[i] = static_cast<unsigned>(i);
      rays.flags[i] = 0;
    }
    rtcOccluded8(valid, state_->scene, &context, &rays);
    for (int i = 0; i < 8; ++i)
      if (valid[i] && rays.tfar[i] >= 0.0f) ++unblocked;
  }
  return unblocked;
}

}  // namespace bounce
