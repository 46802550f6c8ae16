// make_patch_mesh: the OpenMesh patch mesher. OpenMesh stays inside this
// file; the rest of Bounce sees the flat patch_mesh.
#include <OpenMesh/Core/IO/MeshIO.hh>  // must precede the kernel (OpenMesh's rule)
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <queue>
#include <tuple>
#include <vector>

#include "base/check.h"
#include "mesh/a_priori_refinement.h"
#include "mesh/coplanar_cut.h"
#include "mesh/patch_mesh.h"
#include "mesh/shadow_outlines.h"
#include "scene/framing.h"
#include "scene/scene_info.h"
#include "scene/tessellate.h"
#include "scene/texture.h"

namespace bounce {
namespace {

struct mesh_traits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using om_mesh = OpenMesh::TriMesh_ArrayKernelT<mesh_traits>;

vec3 to_glm(const OpenMesh::Vec3d& p) {
  return {p[0], p[1], p[2]};
}
OpenMesh::Vec3d to_om(const vec3& p) {
  return {p.x, p.y, p.z};
}

// The working mesh and what each vertex and face carries.
struct working_mesh {
  om_mesh mesh;
  OpenMesh::VPropHandleT<vec3> normal_sum;  // area-weighted normals of the welded corners
  OpenMesh::VPropHandleT<int> vertex_material;
  OpenMesh::VPropHandleT<int> vertex_surface;
  OpenMesh::VPropHandleT<vec2> vertex_uv;
  OpenMesh::FPropHandleT<int> face_material;
  OpenMesh::FPropHandleT<int> face_surface;
  OpenMesh::FPropHandleT<bool> face_flat;  // from a polygon: may be refined by bisection
  OpenMesh::FPropHandleT<int> face_patch;  // index of the coarse triangle it refines

  working_mesh() {
    mesh.add_property(face_patch);
    mesh.add_property(normal_sum);
    mesh.add_property(vertex_material);
    mesh.add_property(vertex_surface);
    mesh.add_property(vertex_uv);
    mesh.add_property(face_material);
    mesh.add_property(face_surface);
    mesh.add_property(face_flat);
  }
};

// Welds corners of one surface's triangles: same position (exactly: the
// tessellator already merged what should be merged), same material, and
// normals closer than the crease angle share one vertex. Corners of a
// textured material must also agree on uv, so that the renderer can
// interpolate uv per vertex across a texture seam.
struct welder {
  working_mesh& w;
  int surface;
  double cos_crease;
  const std::vector<material>& materials;
  struct candidate {
    om_mesh::VertexHandle vertex;
    vec3 normal;  // the first corner's normal: comparing against a running mean would drift
  };
  using key = std::tuple<std::uint64_t, std::uint64_t, std::uint64_t, int, std::uint64_t, std::uint64_t>;
  std::map<key, std::vector<candidate>> by_key;

  static std::uint64_t bits(double d) {
    if (d == 0.0) d = 0.0;  // -0 and +0 are one position
    std::uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
  }

  om_mesh::VertexHandle vertex_for(const vec3& p, const vec3& n, int material, const vec2& uv) {
    const bool textured = materials[std::size_t(material)].texture >= 0;
    auto& list =
        by_key[{bits(p.x), bits(p.y), bits(p.z), material, textured ? bits(uv.x) : 0, textured ? bits(uv.y) : 0}];
    for (const candidate& c : list)
      if (glm::dot(c.normal, n) >= cos_crease) return c.vertex;
    return list.emplace_back(candidate{new_vertex(p, material, uv), n}).vertex;
  }

  om_mesh::VertexHandle new_vertex(const vec3& p, int material, const vec2& uv) {
    om_mesh::VertexHandle v = w.mesh.add_vertex(to_om(p));
    w.mesh.property(w.normal_sum, v) = vec3(0.0);
    w.mesh.property(w.vertex_material, v) = material;
    w.mesh.property(w.vertex_surface, v) = surface;
    w.mesh.property(w.vertex_uv, v) = uv;
    return v;
  }
};

void add_surface(working_mesh& w, const triangle_mesh& tess, int surface, bool flat, double cos_crease,
                 const std::vector<material>& materials, std::size_t& nonmanifold) {
  welder weld{w, surface, cos_crease, materials, {}};
  for (std::size_t t = 0; t < tess.triangles.size(); ++t) {
    const glm::ivec3 tri = tess.triangles[t];
    const int material = tess.materials[t];
    const vec3 p[3] = {tess.positions[tri[0]], tess.positions[tri[1]], tess.positions[tri[2]]};
    const vec3 cross = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double area = 0.5 * glm::length(cross);
    if (!(area > 0.0)) continue;
    om_mesh::VertexHandle v[3];
    for (int k = 0; k < 3; ++k) v[k] = weld.vertex_for(p[k], tess.normals[tri[k]], material, tess.uvs[tri[k]]);
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    om_mesh::FaceHandle f = w.mesh.add_face(v[0], v[1], v[2]);
    if (!f.is_valid()) {
      // A non-manifold configuration (e.g. three faces on one edge): keep
      // the face with its own vertices rather than losing it.
      ++nonmanifold;
      for (int k = 0; k < 3; ++k) v[k] = weld.new_vertex(p[k], material, tess.uvs[tri[k]]);
      f = w.mesh.add_face(v[0], v[1], v[2]);
    }
    for (int k = 0; k < 3; ++k) w.mesh.property(w.normal_sum, v[k]) += area * tess.normals[tri[k]];
    w.mesh.property(w.face_material, f) = material;
    w.mesh.property(w.face_surface, f) = surface;
    w.mesh.property(w.face_flat, f) = flat;
  }
}

bool edge_is_flat(const working_mesh& w, om_mesh::EdgeHandle e) {
  for (int side = 0; side < 2; ++side) {
    om_mesh::FaceHandle f = w.mesh.face_handle(w.mesh.halfedge_handle(e, side));
    if (f.is_valid() && !w.mesh.property(w.face_flat, f)) return false;
  }
  return true;
}

// Longest-edge bisection (Rivara): always split the longest edge left. A
// split's new edges are medians, never longer than the edge split, so each
// split takes the longest edge of both its triangles: angles stay bounded.
bool refine_flat_faces(working_mesh& w, double max_edge, std::string& error) {
  om_mesh& m = w.mesh;
  // Lengths are ranked in units of max_edge rounded to 1e-9, so that equal
  // edges tie exactly and the mesh does not depend on the scene's units.
  auto rank = [&](om_mesh::EdgeHandle e) { return std::llround(m.calc_edge_length(e) / max_edge * 1e9); };
  const long long limit = std::llround(1e9);
  using entry = std::pair<long long, int>;
  std::priority_queue<entry> longest;
  auto consider = [&](om_mesh::EdgeHandle e) {
    const long long r = rank(e);
    if (r > limit && edge_is_flat(w, e)) longest.push({r, -e.idx()});  // ties: lowest index first
  };
  for (om_mesh::EdgeHandle e : m.edges()) consider(e);
  while (!longest.empty()) {
    auto [length, index] = longest.top();
    longest.pop();
    om_mesh::EdgeHandle e(-index);
    if (rank(e) != length) continue;  // stale: this handle was split since
    om_mesh::HalfedgeHandle h = m.halfedge_handle(e, 0);
    om_mesh::VertexHandle a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
    om_mesh::VertexHandle mid = m.add_vertex(0.5 * (m.point(a) + m.point(b)));
    m.property(w.normal_sum, mid) =
        glm::normalize(m.property(w.normal_sum, a)) + glm::normalize(m.property(w.normal_sum, b));
    m.property(w.vertex_material, mid) = m.property(w.vertex_material, a);
    m.property(w.vertex_surface, mid) = m.property(w.vertex_surface, a);
    m.property(w.vertex_uv, mid) = 0.5 * (m.property(w.vertex_uv, a) + m.property(w.vertex_uv, b));
    m.split_copy(e, mid);  // copies the face properties to the new faces
    if (m.n_faces() > max_patch_elements) {
      error = "the patch mesh would exceed " + std::to_string(max_patch_elements) + " elements at max edge " +
              std::to_string(max_edge) + "; use a larger --max-edge";
      return false;
    }
    for (om_mesh::HalfedgeHandle out : m.voh_range(mid)) consider(m.edge_handle(out));
  }
  return true;
}

// Where a boundary vertex is evaluated: a hair inside one of its own
// faces, towards that face's centroid, so the point stays on the mesh (a
// step along the tangent plane would leave a curved, faceted surface). The
// face is the one whose direction is closest to the mean inward direction.
vec3 receive_point(const om_mesh& m, om_mesh::VertexHandle v) {
  const vec3 p = to_glm(m.point(v));
  if (!m.is_boundary(v)) return p;
  vec3 mean(0.0);
  std::vector<vec3> towards;
  for (om_mesh::FaceHandle f : m.vf_range(v)) {
    vec3 centroid(0.0);
    for (om_mesh::VertexHandle u : m.fv_range(f)) centroid += to_glm(m.point(u));
    towards.push_back(glm::normalize(centroid / 3.0 - p));
    mean += towards.back();
  }
  double edge_sum = 0.0;
  int edges = 0;
  for (om_mesh::HalfedgeHandle h : m.voh_range(v)) {
    edge_sum += m.calc_edge_length(h);
    ++edges;
  }
  if (towards.empty() || edges == 0) return p;
  vec3 best = towards[0];
  for (const vec3& d : towards)
    if (glm::dot(d, mean) > glm::dot(best, mean)) best = d;
  return p + best * (1e-3 * edge_sum / edges);
}
// Appends element `tri` of the finished mesh with its geometric data.
void append_element(patch_mesh& pm, const glm::ivec3& tri, int surface, int material, int patch) {
  const vec3 cross =
      glm::cross(pm.positions[tri[1]] - pm.positions[tri[0]], pm.positions[tri[2]] - pm.positions[tri[0]]);
  pm.elements.push_back(tri);
  pm.element_areas.push_back(0.5 * glm::length(cross));
  pm.element_normals.push_back(glm::normalize(cross));
  pm.element_surfaces.push_back(surface);
  pm.element_materials.push_back(material);
  pm.element_patches.push_back(patch);
}

glm::ivec3 face_vertices(const om_mesh& m, om_mesh::FaceHandle f) {
  glm::ivec3 tri;
  int k = 0;
  for (om_mesh::VertexHandle v : m.fv_range(f)) tri[k++] = v.idx();
  return tri;
}

}  // namespace

double estimate_patch_elements(const scene& s, double max_edge) {
  double estimate = 0.0;
  for (const surface& surf : s.surfaces) {
    if (const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry)) {
      for (const polygon_face& f : mesh->faces) {
        if (f.position.size() < 3) continue;
        vec3 newell(0.0);  // twice the face's vector area
        for (std::size_t k = 0; k < f.position.size(); ++k)
          newell += glm::cross(mesh->positions[std::size_t(f.position[k])],
                               mesh->positions[std::size_t(f.position[(k + 1) % f.position.size()])]);
        estimate += std::max(double(f.position.size() - 2), 0.5 * glm::length(newell) / (0.25 * max_edge * max_edge));
      }
    } else {
      estimate += double(estimate_triangles(surf, max_edge));
    }
  }
  return estimate;
}

bool make_patch_mesh(const scene& s, const mesher_params& params, patch_mesh& out, std::string& error) {
  const double max_edge = params.max_edge > 0.0 ? params.max_edge : default_max_edge(s);
  const double cos_crease = std::cos(glm::radians(params.crease_angle_degrees));

  // Refuse absurd requests before allocating.
  const double estimate = estimate_patch_elements(s, max_edge);
  if (estimate > double(max_patch_elements)) {
    char text[160];  // %g: the estimate may be far beyond any integer type
    std::snprintf(text, sizeof text, "max edge %g would make %s %.3g elements (limit %zu); use a larger --max-edge",
                  max_edge, std::isfinite(estimate) ? "about" : "more than", std::min(estimate, 1e308),
                  std::size_t(max_patch_elements));
    error = text;
    return false;
  }

  // Every surface tessellated first, so that coplanar overlaps (a light in
  // the ceiling's plane) can be cut out of the surface behind before meshing.
  const bounds3 b = scene_bounds(s);
  std::vector<triangle_mesh> tessellated;
  std::vector<bool> flat;
  for (const surface& surf : s.surfaces) {
    tessellated.push_back(tessellate(surf, max_edge));
    flat.push_back(std::holds_alternative<polygon_mesh>(surf.geometry));
  }
  const coplanar_cut_stats cuts = cut_coplanar_overlaps(tessellated, flat, s.materials, glm::length(b.max - b.min));
  const contact_cut_stats contacts = cut_buried_contacts(tessellated, flat, glm::length(b.max - b.min), 0.1 * max_edge);
  const shadow_outline_stats shadows =
      params.shadow_outlines
          ? cut_shadow_outlines(tessellated, flat, s.materials, s.lights, glm::length(b.max - b.min), max_edge)
          : shadow_outline_stats{};
  working_mesh w;
  std::size_t nonmanifold = 0;
  // OpenMesh prints "complex edge" for every face it refuses; add_surface
  // counts them and keeps them, and the caller warns once with the count.
  ::omerr().disable();
  for (std::size_t i = 0; i < s.surfaces.size(); ++i)
    add_surface(w, tessellated[i], static_cast<int>(i), flat[i], cos_crease, s.materials, nonmanifold);
  ::omerr().flush();  // while disabled: drops what was buffered
  ::omerr().enable();
  tessellated.clear();
  // Two levels of bisection: to the patch size, where each face becomes a
  // patch, then to the element size; split_copy hands the patch index down.
  const double patch_edge = std::max(params.patch_edge, max_edge);
  if (!refine_flat_faces(w, patch_edge, error)) return false;
  std::vector<std::array<vec3, 3>> patch_corners;
  for (om_mesh::FaceHandle f : w.mesh.faces()) {
    w.mesh.property(w.face_patch, f) = int(patch_corners.size());
    std::array<vec3, 3> corners;
    int k = 0;
    for (om_mesh::VertexHandle v : w.mesh.fv_range(f)) corners[k++] = to_glm(w.mesh.point(v));
    patch_corners.push_back(corners);
  }
  if (patch_edge > max_edge && !refine_flat_faces(w, max_edge, error)) return false;

  const om_mesh& m = w.mesh;
  patch_mesh pm;
  pm.scene_diagonal = std::max(glm::length(b.max - b.min), 1e-300);
  pm.max_edge = max_edge;
  for (bool is_flat : flat) pm.curved_surfaces.push_back(!is_flat);
  const std::size_t nv = m.n_vertices();
  pm.positions.resize(nv);
  pm.normals.resize(nv);
  pm.receive_points.resize(nv);
  pm.vertex_rho.resize(nv);
  pm.vertex_emission.resize(nv);
  pm.vertex_surfaces.resize(nv);
  pm.uvs.resize(nv);
  for (om_mesh::VertexHandle v : m.vertices()) {
    const int i = v.idx();
    const material& mat = s.materials[m.property(w.vertex_material, v)];
    pm.positions[i] = to_glm(m.point(v));
    vec3 n = m.property(w.normal_sum, v);
    pm.normals[i] = glm::length(n) > 0.0 ? glm::normalize(n) : vec3(0, 1, 0);
    pm.receive_points[i] = receive_point(m, v);
    pm.vertex_rho[i] = mat.texture >= 0 ? mat.rho * texture_mean(s.textures[mat.texture]) : mat.rho;
    pm.vertex_emission[i] = std::numbers::pi * mat.ke;
    pm.vertex_surfaces[i] = m.property(w.vertex_surface, v);
    pm.uvs[i] = m.property(w.vertex_uv, v);
  }
  for (om_mesh::FaceHandle f : m.faces())
    append_element(pm, face_vertices(m, f), m.property(w.face_surface, f), m.property(w.face_material, f),
                   m.property(w.face_patch, f));
  for (const auto& corners : patch_corners) {
    const vec3 cross = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    pm.patch_corners.push_back(corners);
    pm.patch_normals.push_back(glm::normalize(cross));
    pm.patch_areas.push_back(0.5 * glm::length(cross));
  }
  pm.nonmanifold_faces = nonmanifold;
  pm.uncut_overlaps = cuts.pieces_left_uncut + contacts.pieces_left_uncut;
  pm.contact_footprints = contacts.footprints;
  pm.contact_area_removed = contacts.area_removed;
  pm.contact_outline = contacts.outline;
  pm.shadow_lights = shadows.lights;
  pm.shadow_outlines = shadows.shadows;
  pm.shadow_triangles_split = shadows.triangles_split;
  for (double min_edge : {params.a_priori_min_edge, params.solver_min_edge})
    if (min_edge > 0.0 && min_edge < max_edge / 256.0) {
      error = "min edge " + std::to_string(min_edge) + " is below max edge / 256 (" + std::to_string(max_edge / 256.0) +
              "); use a larger --min-edge";
      return false;
    }
  if (params.a_priori_min_edge > 0.0) {
    refinement_pass report;
    if (!refine_a_priori(pm, params.a_priori_min_edge, report, error)) return false;
    if (params.a_priori_report) *params.a_priori_report = report;
  }
  out = std::move(pm);
  return true;
}

namespace {

// The longest edge of a face; equal lengths are ordered by edge index, so
// that "longest" is a strict order and LEPP paths end.
om_mesh::HalfedgeHandle longest_halfedge(const om_mesh& m, om_mesh::FaceHandle f) {
  om_mesh::HalfedgeHandle best;
  double best_length = -1.0;
  for (om_mesh::HalfedgeHandle h : m.fh_range(f)) {
    const double length = m.calc_edge_sqr_length(h);
    if (length > best_length || (length == best_length && m.edge_handle(h).idx() < m.edge_handle(best).idx())) {
      best = h;
      best_length = length;
    }
  }
  return best;
}

}  // namespace

bool refine_patch_mesh(patch_mesh& mesh, std::span<const int> marked, double min_edge, std::vector<int>& origin,
                       std::string& error, std::span<const int> times) {
  const std::size_t old_vertices = mesh.vertex_count();
  const std::size_t old_elements = mesh.element_count();
  const bool has_uvs = mesh.uvs.size() == old_vertices;
  // Surfaces share no vertices, so a bisection never leaves its surface:
  // only the surfaces with a marked element need the half-edge structure
  // (a large scene refined in a few places stays cheap).
  int surfaces = 0;
  for (int surface : mesh.element_surfaces) surfaces = std::max(surfaces, surface + 1);
  std::vector<bool> touched(std::size_t(surfaces), false);
  for (int e : marked)
    if (e >= 0 && std::size_t(e) < old_elements) touched[std::size_t(mesh.element_surfaces[std::size_t(e)])] = true;

  om_mesh m;
  OpenMesh::VPropHandleT<int> parent;  // the old vertex whose surface, material and normal side it shares
  OpenMesh::VPropHandleT<vec3> normal;
  OpenMesh::VPropHandleT<vec2> uv;
  OpenMesh::FPropHandleT<int> face_origin, face_surface, face_material, face_patch;
  OpenMesh::FPropHandleT<bool> face_split;    // bisected in this round (copied to both children)
  OpenMesh::FPropHandleT<bool> face_changed;  // bisected in any round
  OpenMesh::FPropHandleT<int> face_rounds;    // bisections still asked for
  m.add_property(parent);
  m.add_property(normal);
  m.add_property(uv);
  m.add_property(face_origin);
  m.add_property(face_surface);
  m.add_property(face_material);
  m.add_property(face_patch);
  m.add_property(face_split);
  m.add_property(face_changed);
  m.add_property(face_rounds);
  for (std::size_t v = 0; v < old_vertices; ++v) {
    om_mesh::VertexHandle h = m.add_vertex(to_om(mesh.positions[v]));
    m.property(parent, h) = int(v);
    m.property(normal, h) = mesh.normals[v];
    m.property(uv, h) = has_uvs ? mesh.uvs[v] : vec2(0.0);
  }
  std::vector<int> face_of(old_elements, -1);
  for (std::size_t e = 0; e < old_elements; ++e) {
    if (!touched[std::size_t(mesh.element_surfaces[e])]) continue;
    const glm::ivec3 t = mesh.elements[e];
    om_mesh::FaceHandle f =
        m.add_face(om_mesh::VertexHandle(t[0]), om_mesh::VertexHandle(t[1]), om_mesh::VertexHandle(t[2]));
    if (!f.is_valid()) {
      error = "element " + std::to_string(e) + " cannot be rebuilt for refinement (non-manifold)";
      return false;
    }
    face_of[e] = f.idx();
    m.property(face_origin, f) = int(e);
    m.property(face_surface, f) = mesh.element_surfaces[e];
    m.property(face_material, f) = mesh.element_materials[e];
    m.property(face_patch, f) = mesh.element_patches[e];
    m.property(face_split, f) = false;
    m.property(face_changed, f) = false;
    m.property(face_rounds, f) = 0;
  }
  for (std::size_t i = 0; i < marked.size(); ++i) {
    const int e = marked[i];
    if (e < 0 || std::size_t(e) >= old_elements) continue;
    int& rounds = m.property(face_rounds, om_mesh::FaceHandle(face_of[std::size_t(e)]));
    rounds = std::max(rounds, times.empty() ? 1 : times[i]);
  }

  // Rivara's LEPP bisection: follow the longest-edge propagation path from
  // the marked face to a terminal edge (the longest edge of both faces
  // beside it, or a boundary edge), bisect it, and repeat until the marked
  // face itself has been bisected. Only longest edges are ever split, so
  // angles stay bounded and no split leaves a hanging vertex.
  auto split = [&](om_mesh::EdgeHandle e) {
    om_mesh::HalfedgeHandle h = m.halfedge_handle(e, 0);
    om_mesh::VertexHandle a = m.from_vertex_handle(h), b = m.to_vertex_handle(h);
    const int surface = mesh.vertex_surfaces[std::size_t(m.property(parent, a))];
    const bool curved =
        std::size_t(surface) < mesh.curved_surfaces.size() && mesh.curved_surfaces[std::size_t(surface)];
    const vec3 pa = to_glm(m.point(a)), pb = to_glm(m.point(b));
    const vec3 middle =
        curved ? curved_edge_point(pa, m.property(normal, a), pb, m.property(normal, b), 0.5) : 0.5 * (pa + pb);
    om_mesh::VertexHandle mid = m.add_vertex(to_om(middle));
    m.property(parent, mid) = m.property(parent, a);
    m.property(normal, mid) = glm::normalize(m.property(normal, a) + m.property(normal, b));
    m.property(uv, mid) = 0.5 * (m.property(uv, a) + m.property(uv, b));
    for (int side = 0; side < 2; ++side) {
      om_mesh::FaceHandle f = m.face_handle(m.halfedge_handle(e, side));
      if (f.is_valid()) m.property(face_split, f) = m.property(face_changed, f) = true;
    }
    m.split_copy(e, mid);
  };
  const double min_length = min_edge * min_edge;
  const std::size_t untouched = std::size_t(std::count(face_of.begin(), face_of.end(), -1));
  std::vector<om_mesh::FaceHandle> path, round;
  for (;;) {
    // One round: every face still asking for a bisection gets one; its
    // two halves then ask for one fewer.
    round.clear();
    for (om_mesh::FaceHandle f : m.faces())
      if (m.property(face_rounds, f) > 0) round.push_back(f);
    if (round.empty()) break;
    for (om_mesh::FaceHandle f : m.faces()) m.property(face_split, f) = false;
    for (om_mesh::FaceHandle f : round) {
      if (m.property(face_split, f)) continue;  // already split on another face's path
      if (m.calc_edge_sqr_length(longest_halfedge(m, f)) <= min_length) continue;
      path.assign(1, f);
      while (!path.empty()) {
        om_mesh::FaceHandle t = path.back();
        om_mesh::HalfedgeHandle h = longest_halfedge(m, t);
        om_mesh::FaceHandle next = m.opposite_face_handle(h);
        if (next.is_valid() && m.edge_handle(longest_halfedge(m, next)) != m.edge_handle(h)) {
          path.push_back(next);
          continue;
        }
        split(m.edge_handle(h));
        path.pop_back();
        // The marked face is done once it is split; faces earlier on the path
        // were only there to reach it.
        if (!path.empty() && m.property(face_split, path.front())) break;
      }
      if (untouched + m.n_faces() > max_patch_elements) {
        error = "refinement would exceed " + std::to_string(max_patch_elements) + " elements; use a larger --min-edge";
        return false;
      }
    }
    // Faces split (for themselves or for a neighbour) use up a round;
    // marked faces that could not be split (at the minimum edge) stop.
    for (om_mesh::FaceHandle f : m.faces()) {
      int& rounds = m.property(face_rounds, f);
      rounds = m.property(face_split, f) ? std::max(0, rounds - 1) : 0;
    }
  }

  patch_mesh out;
  out.scene_diagonal = mesh.scene_diagonal;
  out.max_edge = mesh.max_edge;
  out.curved_surfaces = std::move(mesh.curved_surfaces);
  out.nonmanifold_faces = mesh.nonmanifold_faces;
  out.uncut_overlaps = mesh.uncut_overlaps;
  out.contact_footprints = mesh.contact_footprints;
  out.contact_area_removed = mesh.contact_area_removed;
  out.contact_outline = mesh.contact_outline;
  out.shadow_lights = mesh.shadow_lights;
  out.shadow_outlines = mesh.shadow_outlines;
  out.shadow_triangles_split = mesh.shadow_triangles_split;
  out.positions = std::move(mesh.positions);
  out.normals = std::move(mesh.normals);
  out.receive_points = std::move(mesh.receive_points);
  out.vertex_rho = std::move(mesh.vertex_rho);
  out.vertex_emission = std::move(mesh.vertex_emission);
  out.vertex_surfaces = std::move(mesh.vertex_surfaces);
  if (has_uvs) out.uvs = std::move(mesh.uvs);
  // Old vertices keep everything, their receive points included: their
  // radiosity was computed there. New ones copy their parent's attributes.
  for (std::size_t v = old_vertices; v < m.n_vertices(); ++v) {
    const om_mesh::VertexHandle h{int(v)};
    const int p = m.property(parent, h);
    out.positions.push_back(to_glm(m.point(h)));
    out.normals.push_back(m.property(normal, h));
    out.receive_points.push_back(receive_point(m, h));
    out.vertex_rho.push_back(out.vertex_rho[p]);
    out.vertex_emission.push_back(out.vertex_emission[p]);
    out.vertex_surfaces.push_back(out.vertex_surfaces[p]);
    if (has_uvs) out.uvs.push_back(m.property(uv, h));
  }
  // A patch that was a single element stays its element: its children
  // become patches of their own (the reference discretisation).
  std::vector<int> patch_size(mesh.patch_count(), 0);
  for (int p : mesh.element_patches) ++patch_size[p];
  out.patch_corners = std::move(mesh.patch_corners);
  out.patch_normals = std::move(mesh.patch_normals);
  out.patch_areas = std::move(mesh.patch_areas);
  std::vector<bool> patch_taken(patch_size.size(), false);
  origin.clear();
  // The untouched surfaces' elements first, as they were; then the faces
  // of the refined surfaces.
  for (std::size_t e = 0; e < old_elements; ++e) {
    if (face_of[e] >= 0) continue;
    append_element(out, mesh.elements[e], mesh.element_surfaces[e], mesh.element_materials[e], mesh.element_patches[e]);
    origin.push_back(int(e));
  }
  for (om_mesh::FaceHandle f : m.faces()) {
    const glm::ivec3 tri = face_vertices(m, f);
    int patch = m.property(face_patch, f);
    append_element(out, tri, m.property(face_surface, f), m.property(face_material, f), patch);
    origin.push_back(m.property(face_origin, f));
    if (patch_size[patch] == 1 && m.property(face_changed, f)) {
      if (patch_taken[patch]) {
        patch = int(out.patch_areas.size());
        out.patch_corners.emplace_back();
        out.patch_normals.emplace_back();
        out.patch_areas.emplace_back();
        out.element_patches.back() = patch;
      } else {
        patch_taken[patch] = true;
      }
      out.patch_corners[patch] = {out.positions[tri[0]], out.positions[tri[1]], out.positions[tri[2]]};
      out.patch_normals[patch] = out.element_normals.back();
      out.patch_areas[patch] = out.element_areas.back();
    }
  }
  mesh = std::move(out);
  return true;
}

void check_mesh_contract(const patch_mesh& mesh) {
  const std::size_t vertices = mesh.vertex_count(), elements = mesh.element_count();
  BOUNCE_CHECK_EQ(mesh.vertex_emission.size(), vertices);
  BOUNCE_CHECK_EQ(mesh.element_patches.size(), elements);
  for (std::size_t e = 0; e < elements; ++e) {
    const glm::ivec3 t = mesh.elements[e];
    BOUNCE_CHECK(t[0] >= 0 && t[1] >= 0 && t[2] >= 0);
    BOUNCE_CHECK_LT(std::size_t(std::max({t[0], t[1], t[2]})), vertices);
    BOUNCE_CHECK_LT(std::size_t(mesh.element_patches[e]), mesh.patch_count());
  }
}

vec3 barycentric(const patch_mesh& mesh, int element, const vec3& point) {
  const auto [a, b, c] = element_corners(mesh, std::size_t(element));
  const vec3 n = glm::cross(b - a, c - a);
  const double inv = 1.0 / glm::dot(n, n);
  const double wa = glm::dot(glm::cross(c - b, point - b), n) * inv;
  const double wb = glm::dot(glm::cross(a - c, point - c), n) * inv;
  return {wa, wb, 1.0 - wa - wb};
}

double total_area(const patch_mesh& mesh) {
  double sum = 0.0;
  for (double a : mesh.element_areas) sum += a;
  return sum;
}

}  // namespace bounce
