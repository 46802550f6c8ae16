#include "scene/scene_io.h"

#include <cctype>
#include <new>
#include <variant>

#include "scene/assimp_io.h"
#include "scene/framing.h"
#include "scene/gltf_io.h"
#include "scene/json_scene.h"
#include "scene/obj_io.h"
#include "scene/procedural.h"
#include "scene/reader_support.h"
#include "scene/scene_validate.h"
#include "scene/tessellate.h"
#include "scene/two_sided.h"

namespace bounce {
namespace {

bool ends_with_icase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

// Drops degenerate polygon faces (fewer than 3 distinct corners, zero area),
// counting them; the triangulator owns the definition of "degenerate".
void drop_degenerate_faces(scene& s, load_report& report) {
  for (surface& surf : s.surfaces) {
    auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    if (!mesh) continue;
    std::vector<polygon_face> kept;
    for (polygon_face& f : mesh->faces) {
      // A one-face copy holding only this face's corners.
      polygon_mesh single;
      polygon_face probe;
      for (int i : f.position) {
        probe.position.push_back(static_cast<int>(single.positions.size()));
        single.positions.push_back(mesh->positions[i]);
      }
      single.faces = {probe};
      std::size_t dropped = 0;
      triangulate(single, &dropped);
      if (dropped) {
        ++report.dropped_faces;
        std::string where = f.line ? surf.source + ":" + std::to_string(f.line) : surf.source + ": " + surf.name;
        report.warnings.push_back(where + ": degenerate face (zero area) dropped");
      } else {
        kept.push_back(std::move(f));
      }
    }
    mesh->faces = std::move(kept);
  }
  std::erase_if(s.surfaces, [](const surface& surf) {
    auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    return mesh && mesh->faces.empty();
  });
}

// Emitting polygon surfaces whose light reaches nothing: for every one of
// their emitting faces, all other geometry lies behind the face's plane or
// turns its back to the face (radiosity's form factors are then zero, and
// the picture black). Light leaves the side from which the corners run
// anticlockwise. Curved emitters and point lights shine all round; they
// are not checked. One warning per surface.
void warn_unreachable_emitters(const scene& s, load_report& report) {
  struct face_ref {
    const polygon_mesh* mesh;
    const polygon_face* face;
    vec3 centroid, normal;  // normal: unit, or zero for a degenerate face
  };
  std::vector<face_ref> faces;
  std::vector<std::size_t> first_face;  // per surface: where its faces begin in `faces`
  std::vector<bounds3> curved;          // boxes of curved surfaces: receivers seen from any side
  for (const surface& surf : s.surfaces) {
    first_face.push_back(faces.size());
    if (const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry)) {
      for (const polygon_face& f : mesh->faces) {
        vec3 newell(0.0), centroid(0.0);
        for (std::size_t i = 0; i < f.position.size(); ++i) {
          newell +=
              glm::cross(mesh->positions[f.position[i]], mesh->positions[f.position[(i + 1) % f.position.size()]]);
          centroid += mesh->positions[f.position[i]];
        }
        const double length = glm::length(newell);
        faces.push_back({mesh, &f, centroid / double(f.position.size()), length > 0.0 ? newell / length : vec3(0.0)});
      }
    } else {
      scene one;
      one.surfaces.push_back(surf);
      curved.push_back(scene_bounds(one));
    }
  }
  first_face.push_back(faces.size());  // one past the last surface's
  const bounds3 all = scene_bounds(s);
  const double eps = 1e-9 * glm::length(all.max - all.min);
  auto in_front = [&](const vec3& p, const face_ref& f) { return glm::dot(p - f.centroid, f.normal) > eps; };
  auto any_corner_in_front = [&](const face_ref& of, const face_ref& f) {
    for (int i : of.face->position)
      if (in_front(of.mesh->positions[i], f)) return true;
    return false;
  };
  auto emits = [&](int material) { return any_positive(s.materials[material].ke); };
  std::size_t emitting_faces = 0;
  for (const face_ref& f : faces) emitting_faces += emits(f.face->material) ? 1 : 0;
  // A scene of many emitting faces is not checked: the test is quadratic.
  if (double(emitting_faces) * double(faces.size()) > 2e7) return;

  for (std::size_t surface_index = 0; surface_index < s.surfaces.size(); ++surface_index) {
    const surface& surf = s.surfaces[surface_index];
    if (!std::holds_alternative<polygon_mesh>(surf.geometry)) continue;
    bool emitting = false, reaches = false;
    std::string material_name;
    for (std::size_t at = first_face[surface_index]; at < first_face[surface_index + 1] && !reaches; ++at) {
      const face_ref& e = faces[at];
      if (!emits(e.face->material)) continue;
      if (!emitting) material_name = s.materials[e.face->material].name;
      emitting = true;
      if (e.normal == vec3(0.0)) continue;
      for (const face_ref& r : faces)
        if (&r != &e && r.normal != vec3(0.0) && any_corner_in_front(r, e) && any_corner_in_front(e, r)) {
          reaches = true;
          break;
        }
      for (const bounds3& b : curved)
        for (int corner = 0; corner < 8 && !reaches; ++corner)
          reaches = in_front(
              vec3(corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y, corner & 4 ? b.max.z : b.min.z), e);
    }
    if (emitting && !reaches)
      report.warnings.push_back(s.source + ": surface '" + surf.name + "' emits (material '" + material_name +
                                "') but faces away from every other surface: its light reaches nothing (light "
                                "leaves the side from which its corners run anticlockwise)");
  }
}

}  // namespace

bool load_scene(const std::string& path, scene& out, load_report& report) {
  report = {};
  input_log inputs;
  struct keep_inputs {  // on every way out, failures included
    input_log& log;
    load_report& report;
    ~keep_inputs() { report.inputs = std::move(log.files); }
  } keep{inputs, report};
  scene s;
  s.source = path;
  try {
    if (ends_with_icase(path, ".obj")) {
      obj_read_result obj = read_obj(path, s.materials, s.textures);
      s.surfaces = std::move(obj.surfaces);
      report.warnings = std::move(obj.warnings);
      report.dropped_faces = obj.dropped_faces;
      s.view = fit_camera(s);
    } else if (ends_with_icase(path, ".gltf") || ends_with_icase(path, ".glb")) {
      gltf_read_result gltf = read_gltf(path, s.materials, s.textures);
      s.surfaces = std::move(gltf.surfaces);
      s.lights = std::move(gltf.lights);
      report.warnings = std::move(gltf.warnings);
      s.view = fit_camera(s);
    } else if (read_through_assimp(path)) {
      assimp_read_result model = read_assimp(path, s.materials, s.textures);
      s.surfaces = std::move(model.surfaces);
      report.warnings = std::move(model.warnings);
      s.view = fit_camera(s);
    } else if (path.starts_with(generated_prefix)) {
      std::string error;
      if (!make_procedural_scene(std::string_view(path).substr(generated_prefix.size()), s, error))
        throw load_error(path + ": " + error);
      s.source = path;  // so that reopening it (the panel) builds it again
    } else if (ends_with_icase(path, ".json")) {
      read_json_scene(path, s, report.warnings, report.dropped_faces);
    } else {
      throw load_error(path +
                       ": unknown scene format (expected .json, .obj, .gltf, .glb, .ply, .stl, .dae, .fbx, .3ds, "
                       ".off or generated:NAME)");
    }
    drop_degenerate_faces(s, report);
    for (std::string& w : add_back_sides(s)) report.warnings.push_back(path + ": " + w);
    if (s.surfaces.empty()) throw load_error(path + ": no surfaces left after dropping degenerate faces");
    if (std::string problem = validate_scene(s); !problem.empty()) throw load_error(path + ": " + problem);
    const bool model_file = ends_with_icase(path, ".obj") || ends_with_icase(path, ".gltf") ||
                            ends_with_icase(path, ".glb") || read_through_assimp(path);
    if (model_file && !has_lamp(s)) {
      // Most models come without lights: open them as a viewer would, under a white sky.
      s.sky.zenith = s.sky.horizon = rgb(1.0);
      report.warnings.push_back(path +
                                ": no emitter: lit by a uniform white sky of radiance 1 (a JSON scene with "
                                "\"sky\" or an emitter chooses the light)");
    }
    if (!has_light_source(s))
      report.warnings.push_back(path +
                                ": no emitter: no surface has a material with ke > 0 and there is no "
                                "punctual light, so nothing lights the scene");
    warn_unreachable_emitters(s, report);
  } catch (const load_error& e) {
    report.warnings.insert(report.warnings.end(), e.warnings.begin(), e.warnings.end());
    report.error = e.what();
    return false;
  } catch (const std::bad_alloc&) {
    report.error = path + ": out of memory while reading it (the file is larger than the memory this process may use)";
    return false;
  } catch (const std::exception& e) {
    // Anything else still gets the file named.
    report.error = path + ": " + e.what();
    return false;
  }
  out = std::move(s);
  return true;
}

}  // namespace bounce
