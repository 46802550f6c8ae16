// The hemicube (Cohen & Greenberg 1985), on the CPU: a z-buffer over the
// five faces of a half cube at the shooter's centroid. Each pixel carries a
// delta form factor; the element seen through it receives that share of the
// shooter's power, split over its three vertices by the barycentric weights
// of the point seen. By reciprocity, F(v, e) = A_e * F(e -> v's share) / A_v.
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/parallel_for.h>

#include "radiosity/transfer/hemicube.h"

namespace bounce {
namespace {

using std::numbers::pi;

struct face_frame {
  vec3 u, v, w;       // screen x, screen y, view direction
  int width, height;  // pixels
  double y_min;       // screen y range [y_min, 1]: -1 for the top, 0 for the sides
};

struct face_buffer {
  std::vector<double> depth;  // 1 / distance along w: larger is nearer
  std::vector<int> id;        // element seen, or -1
};

// Clips a convex polygon (local coordinates) to a.x + b.y + c.z >= 0.
int clip(const std::array<vec3, 12>& in, int n, const vec3& plane, std::array<vec3, 12>& out) {
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const vec3& a = in[i];
    const vec3& b = in[(i + 1) % n];
    const double da = glm::dot(plane, a), db = glm::dot(plane, b);
    if (da >= 0.0 && count < 12) out[count++] = a;
    if ((da >= 0.0) != (db >= 0.0) && count < 12) out[count++] = a + (b - a) * (da / (da - db));
  }
  return count;
}

// Rasterises one element into one face: clip to the view frustum, project,
// and fill the covered pixel centres, keeping the nearest.
void rasterize(const face_frame& f, const vec3 (&local)[3], int id, double near, face_buffer& buffer) {
  std::array<vec3, 12> a, b;
  for (int k = 0; k < 3; ++k) a[k] = local[k];
  int n = 3;
  // near plane, then |x| <= z, |y| <= z, and y >= y_min * z for the half faces
  const vec3 planes[] = {{0, 0, 1}, {-1, 0, 1}, {1, 0, 1}, {0, -1, 1}, {0, 1, -f.y_min}};
  for (int i = 0; i < 5 && n >= 3; ++i) {
    if (i == 0) {
      int count = 0;
      for (int k = 0; k < n; ++k) {
        const vec3& p = a[k];
        const vec3& q = a[(k + 1) % n];
        const double dp = p.z - near, dq = q.z - near;
        if (dp >= 0.0) b[count++] = p;
        if ((dp >= 0.0) != (dq >= 0.0)) b[count++] = p + (q - p) * (dp / (dp - dq));
      }
      n = count;
    } else {
      n = clip(a, n, planes[i], b);
    }
    a = b;
  }
  if (n < 3) return;
  // Screen coordinates in pixels, and 1/z, which is linear in screen space.
  std::array<glm::dvec3, 12> s;
  const double sx = f.width / 2.0, sy = f.height / (1.0 - f.y_min);
  for (int k = 0; k < n; ++k) s[k] = {(a[k].x / a[k].z + 1.0) * sx, (a[k].y / a[k].z - f.y_min) * sy, 1.0 / a[k].z};
  for (int k = 1; k + 1 < n; ++k) {
    const glm::dvec3 p0 = s[0], p1 = s[k], p2 = s[k + 1];
    const double area = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
    if (area == 0.0) continue;
    const int x0 = std::max(0, int(std::floor(std::min({p0.x, p1.x, p2.x}))));
    const int x1 = std::min(f.width - 1, int(std::ceil(std::max({p0.x, p1.x, p2.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({p0.y, p1.y, p2.y}))));
    const int y1 = std::min(f.height - 1, int(std::ceil(std::max({p0.y, p1.y, p2.y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        double w0 = ((p1.x - px) * (p2.y - py) - (p2.x - px) * (p1.y - py)) / area;
        double w1 = ((p2.x - px) * (p0.y - py) - (p0.x - px) * (p2.y - py)) / area;
        double w2 = 1.0 - w0 - w1;
        if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
        const double depth = w0 * p0.z + w1 * p1.z + w2 * p2.z;
        const std::size_t i = std::size_t(y) * f.width + x;
        if (depth > buffer.depth[i]) {
          buffer.depth[i] = depth;
          buffer.id[i] = id;
        }
      }
  }
}

}  // namespace

std::uint64_t hemicube_form_factors(const form_factor_context& context, const shooter& from, std::span<double> out) {
  const patch_mesh& mesh = *context.mesh;
  const int resolution = std::max(2, context.params.hemicube_resolution & ~1);
  const vec3 n = from.normal;
  // The eye: the centroid, lifted off the shooter (see the context's offset).
  const vec3 eye = (from.corners[0] + from.corners[1] + from.corners[2]) / 3.0 + n * context.offset;
  const vec3 tangent = glm::normalize(from.corners[1] - from.corners[0]);
  const vec3 bitangent = glm::cross(n, tangent);
  const std::array<face_frame, 5> faces = {{
      {tangent, bitangent, n, resolution, resolution, -1.0},
      {bitangent, n, tangent, resolution, resolution / 2, 0.0},
      {-bitangent, n, -tangent, resolution, resolution / 2, 0.0},
      {-tangent, n, bitangent, resolution, resolution / 2, 0.0},
      {tangent, n, -bitangent, resolution, resolution / 2, 0.0},
  }};
  const double near = context.offset;

  std::array<std::vector<double>, 5> face_share;  // F(e -> each vertex's share of area), per face
  auto render_face = [&](std::size_t fi) {
    const face_frame& f = faces[fi];
    face_buffer buffer{std::vector<double>(std::size_t(f.width) * f.height, 0.0),
                       std::vector<int>(std::size_t(f.width) * f.height, -1)};
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      if (from.contains(mesh, e)) continue;
      vec3 local[3];
      for (int k = 0; k < 3; ++k) {
        const vec3 d = mesh.positions[mesh.elements[e][k]] - eye;
        local[k] = {glm::dot(d, f.u), glm::dot(d, f.v), glm::dot(d, f.w)};
      }
      rasterize(f, local, int(e), near, buffer);
    }
    std::vector<double>& acc = face_share[fi];
    acc.assign(mesh.vertex_count(), 0.0);
    const double pixel_area = (2.0 / f.width) * ((1.0 - f.y_min) / f.height);
    for (int y = 0; y < f.height; ++y)
      for (int x = 0; x < f.width; ++x) {
        const std::size_t i = std::size_t(y) * f.width + x;
        const int seen = buffer.id[i];
        if (seen < 0) continue;
        const double sx = (x + 0.5) / f.width * 2.0 - 1.0;
        const double sy = f.y_min + (y + 0.5) / f.height * (1.0 - f.y_min);
        const vec3 direction = f.u * sx + f.v * sy + f.w;  // unit distance along w
        // Only the front of an element receives; its back still occludes.
        if (glm::dot(mesh.element_normals[seen], direction) >= 0.0) continue;
        // Delta form factor of the pixel: cos at the eye * cos at the
        // pixel / (pi r^4) in face units; the height above the base is the
        // n component of the direction.
        const double r2 = sx * sx + sy * sy + 1.0;
        const double delta = glm::dot(direction, n) * pixel_area / (pi * r2 * r2);
        const vec3 point = eye + direction / buffer.depth[i];
        vec3 weights = glm::clamp(barycentric(mesh, seen, point), 0.0, 1.0);
        weights /= weights.x + weights.y + weights.z;
        for (int k = 0; k < 3; ++k) acc[mesh.elements[seen][k]] += delta * weights[k];
      }
  };
  if (context.params.parallel)
    tbb::parallel_for(std::size_t(0), faces.size(), render_face);
  else
    for (std::size_t fi = 0; fi < faces.size(); ++fi) render_face(fi);

  const double area = from.area;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    double s = 0.0;
    for (const auto& acc : face_share) s += acc[v];
    out[v] = context.vertex_areas[v] > 0.0 ? area * s / context.vertex_areas[v] : 0.0;
  }
  return 0;
}

}  // namespace bounce
