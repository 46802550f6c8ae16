#include "scene/scene_io.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "scene/framing.h"
#include "scene/gltf_io.h"
#include "scene/obj_io.h"
#include "scene/procedural.h"
#include "scene/reader_support.h"
#include "scene/scene_validate.h"
#include "scene/tessellate.h"
#include "scene/two_sided.h"

namespace bounce {
namespace {

using json = nlohmann::json;

bool ends_with_icase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suffix.size() + i])) != suffix[i]) return false;
  return true;
}

// Typed access to a JSON document; every error names the file and the
// value's path inside it (e.g. "materials.white.rho").
struct json_reader {
  std::string file;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw load_error(file + ": " + where + ": " + what);
  }

  void only_keys(const json& j, const std::string& where, std::initializer_list<const char*> allowed) const {
    if (!j.is_object()) fail(where, "must be an object");
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool known = false;
      for (const char* a : allowed) known = known || it.key() == a;
      if (!known) {
        std::string list;
        for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
        fail(where, "unknown key '" + it.key() + "' (expected one of: " + list + ")");
      }
    }
  }

  // Every number in a scene file is finite and at most max_file_number in
  // magnitude (the OBJ reader's limit): intensities, emissions, backgrounds
  // and sizes then cannot overflow in the products made of them.
  double number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "must be a number");
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(where, "must be finite");
    if (std::abs(v) > max_file_number) {
      char text[96];
      std::snprintf(text, sizeof text, "%g is out of range (limit %g in magnitude)", v, max_file_number);
      fail(where, text);
    }
    return v;
  }

  int integer(const json& j, const std::string& where) const {
    if (!j.is_number_integer()) fail(where, "must be an integer");
    auto v = j.get<long long>();
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) fail(where, "is out of range");
    return static_cast<int>(v);
  }

  std::string string(const json& j, const std::string& where) const {
    if (!j.is_string()) fail(where, "must be a string");
    return j.get<std::string>();
  }

  bool boolean(const json& j, const std::string& where) const {
    if (!j.is_boolean()) fail(where, "must be true or false");
    return j.get<bool>();
  }

  template <int N>
  glm::vec<N, double> vec(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != N) fail(where, "must be an array of " + std::to_string(N) + " numbers");
    glm::vec<N, double> v;
    for (int i = 0; i < N; ++i) v[i] = number(j[i], where + "[" + std::to_string(i) + "]");
    return v;
  }

  template <int N>
  std::vector<glm::vec<N, double>> vec_list(const json& j, const std::string& where) const {
    if (!j.is_array()) fail(where, "must be an array");
    std::vector<glm::vec<N, double>> out;
    for (std::size_t i = 0; i < j.size(); ++i) out.push_back(vec<N>(j[i], where + "[" + std::to_string(i) + "]"));
    return out;
  }
};

// Line and column of a byte offset, for JSON syntax errors.
std::string line_column(const std::string& text, std::size_t byte) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

// Byte offset of the first number literal in `text` (outside strings) that
// overflows a double, or npos.
std::size_t first_overflowing_number(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {  // skip the string, escapes included
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      const char* start = text.c_str() + i;
      char* end = nullptr;
      const double v = std::strtod(start, &end);
      if (end == start) continue;
      if (std::isinf(v)) return i;
      i += std::size_t(end - start) - 1;
    }
  }
  return std::string::npos;
}

json parse_json(const std::string& path, const std::string& text) {
  try {
    return json::parse(text);
  } catch (const json::out_of_range& e) {
    // A literal beyond a double (1e400): the library's message has no position.
    const std::size_t at = first_overflowing_number(text);
    if (at == std::string::npos) throw load_error(path + ": invalid JSON: " + e.what());
    std::size_t end = at + 1;
    while (end < text.size() && std::strchr("+-.0123456789eE", text[end])) ++end;
    throw load_error(path + ":" + line_column(text, at) + ": number out of range: " + text.substr(at, end - at));
  } catch (const json::parse_error& e) {
    // e.what() repeats the position in nlohmann's own format; keep only the reason.
    std::string what = e.what();
    if (std::size_t colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    if (std::size_t colon = what.find(": "); what.rfind("syntax error", 0) != 0 && colon != std::string::npos)
      what = what.substr(colon + 2);
    throw load_error(path + ":" + line_column(text, e.byte == 0 ? 0 : e.byte - 1) + ": invalid JSON: " + what);
  }
}

void read_camera(const json_reader& r, const json& j, camera& cam) {
  r.only_keys(j, "camera", {"eye", "target", "up", "fov", "size"});
  if (!j.contains("eye") || !j.contains("target")) r.fail("camera", "needs 'eye' and 'target'");
  cam.eye = r.vec<3>(j["eye"], "camera.eye");
  cam.target = r.vec<3>(j["target"], "camera.target");
  if (j.contains("up")) cam.up = r.vec<3>(j["up"], "camera.up");
  if (j.contains("fov")) cam.fov_y_degrees = r.number(j["fov"], "camera.fov");
  if (j.contains("size")) {
    const json& size = j["size"];
    if (!size.is_array() || size.size() != 2) r.fail("camera.size", "must be [width, height]");
    cam.width = r.integer(size[0], "camera.size[0]");
    cam.height = r.integer(size[1], "camera.size[1]");
  }
}

texture read_texture(const json_reader& r, const std::string& name, const json& j) {
  const std::string where = "textures." + name;
  r.only_keys(j, where, {"checker", "image"});
  if (j.size() != 1) r.fail(where, "needs exactly one of 'checker' or 'image'");
  if (j.contains("image"))
    return read_image_texture(resolve(r.file, r.string(j["image"], where + ".image")), name, r.file + ": " + where);
  const json& c = j["checker"];
  r.only_keys(c, where + ".checker", {"color0", "color1", "scale"});
  texture t;
  t.name = name;
  t.kind = texture_kind::checker;
  if (c.contains("color0")) t.color0 = r.vec<3>(c["color0"], where + ".checker.color0");
  if (c.contains("color1")) t.color1 = r.vec<3>(c["color1"], where + ".checker.color1");
  if (c.contains("scale")) t.scale = r.number(c["scale"], where + ".checker.scale");
  if (!(t.scale > 0.0)) r.fail(where + ".checker.scale", "must be positive");
  return t;
}

material read_material(const json_reader& r, const std::string& name, const json& j,
                       const std::map<std::string, int>& texture_by_name) {
  const std::string where = "materials." + name;
  r.only_keys(j, where, {"rho", "ke", "kr", "kt", "ior", "fresnel", "specular", "shininess", "texture", "two_sided"});
  material m;
  m.name = name;
  if (j.contains("rho")) m.rho = r.vec<3>(j["rho"], where + ".rho");
  if (j.contains("ke")) m.ke = r.vec<3>(j["ke"], where + ".ke");
  if (j.contains("kr")) m.kr = r.vec<3>(j["kr"], where + ".kr");
  if (j.contains("kt")) m.kt = r.vec<3>(j["kt"], where + ".kt");
  if (j.contains("ior")) m.ior = r.number(j["ior"], where + ".ior");
  if (j.contains("fresnel")) m.fresnel = r.boolean(j["fresnel"], where + ".fresnel");
  if (j.contains("specular")) m.specular = r.vec<3>(j["specular"], where + ".specular");
  if (j.contains("shininess")) m.shininess = r.number(j["shininess"], where + ".shininess");
  if (j.contains("two_sided")) m.two_sided = r.boolean(j["two_sided"], where + ".two_sided");
  if (j.contains("texture")) {
    std::string t = r.string(j["texture"], where + ".texture");
    auto it = texture_by_name.find(t);
    if (it == texture_by_name.end()) r.fail(where + ".texture", "no texture named '" + t + "'");
    m.texture = it->second;
  }
  return m;
}

struct scene_builder {
  json_reader r;
  scene& s;
  load_report& report;
  std::map<std::string, int> material_by_name;

  int material_ref(const json& j, const std::string& where) {
    if (!j.contains("material")) r.fail(where, "needs a 'material'");
    std::string name = r.string(j["material"], where + ".material");
    auto it = material_by_name.find(name);
    if (it == material_by_name.end()) r.fail(where + ".material", "no material named '" + name + "'");
    return it->second;
  }

  void read_obj_surface(const json& j, const std::string& where) {
    r.only_keys(j, where, {"obj", "name", "scale", "translate", "material"});
    const std::string file = resolve(r.file, r.string(j["obj"], where + ".obj"));
    double scale = j.contains("scale") ? r.number(j["scale"], where + ".scale") : 1.0;
    if (!(scale > 0.0)) r.fail(where + ".scale", "must be positive");
    vec3 translate = j.contains("translate") ? r.vec<3>(j["translate"], where + ".translate") : vec3(0.0);
    int override_material = j.contains("material") ? material_ref(j, where) : -1;
    obj_read_result obj;
    try {
      obj = read_obj(file, s.materials, s.textures);
    } catch (const load_error& e) {
      // Name the scene file and the surface that asked for the OBJ too.
      load_error named(r.file + ": " + where + ".obj: " + e.what());
      named.warnings = e.warnings;
      throw named;
    }
    report.dropped_faces += obj.dropped_faces;
    report.warnings.insert(report.warnings.end(), obj.warnings.begin(), obj.warnings.end());
    for (surface& surf : obj.surfaces) {
      auto& mesh = std::get<polygon_mesh>(surf.geometry);
      for (vec3& p : mesh.positions) p = p * scale + translate;
      if (override_material >= 0)
        for (polygon_face& f : mesh.faces) f.material = override_material;
      if (j.contains("name")) surf.name = r.string(j["name"], where + ".name") + "/" + surf.name;
      s.surfaces.push_back(std::move(surf));
    }
  }

  void read_surface(const json& j, const std::string& where) {
    if (!j.is_object()) r.fail(where, "must be an object");
    static const char* shapes[] = {"obj", "polygon", "sphere", "quadric", "bezier", "bspline"};
    std::vector<std::string> found;
    for (const char* k : shapes)
      if (j.contains(k)) found.push_back(k);
    if (found.size() != 1)
      r.fail(where, "needs exactly one shape key: obj, polygon, sphere, quadric, bezier or bspline");
    const std::string& kind = found[0];
    if (kind == "obj") return read_obj_surface(j, where);

    surface surf;
    surf.name = j.contains("name") ? r.string(j["name"], where + ".name") : where;
    surf.source = r.file;
    const std::string at = where + "." + kind;
    const json& g = j[kind];
    if (kind == "polygon") {
      r.only_keys(j, where, {"polygon", "uv", "name", "material"});
      polygon_mesh mesh;
      mesh.positions = r.vec_list<3>(g, at);
      if (mesh.positions.size() < 3) r.fail(at, "needs at least 3 vertices");
      polygon_face face;
      face.material = material_ref(j, where);
      for (int i = 0; i < static_cast<int>(mesh.positions.size()); ++i) face.position.push_back(i);
      if (j.contains("uv")) {
        mesh.uvs = r.vec_list<2>(j["uv"], where + ".uv");
        if (mesh.uvs.size() != mesh.positions.size()) r.fail(where + ".uv", "needs one uv per vertex");
        face.uv = face.position;
      }
      mesh.faces.push_back(face);
      surf.geometry = std::move(mesh);
    } else if (kind == "sphere") {
      r.only_keys(j, where, {"sphere", "name", "material"});
      r.only_keys(g, at, {"center", "radius"});
      sphere sp;
      if (!g.contains("center") || !g.contains("radius")) r.fail(at, "needs 'center' and 'radius'");
      sp.center = r.vec<3>(g["center"], at + ".center");
      sp.radius = r.number(g["radius"], at + ".radius");
      sp.material = material_ref(j, where);
      surf.geometry = sp;
    } else if (kind == "quadric") {
      r.only_keys(j, where, {"quadric", "name", "material"});
      r.only_keys(g, at, {"a", "b", "c", "d", "e", "f", "g", "h", "j", "k", "box"});
      quadric q;
      double* coefficient[] = {&q.a, &q.b, &q.c, &q.d, &q.e, &q.f, &q.g, &q.h, &q.j, &q.k};
      const char* names[] = {"a", "b", "c", "d", "e", "f", "g", "h", "j", "k"};
      for (int i = 0; i < 10; ++i)
        if (g.contains(names[i])) *coefficient[i] = r.number(g[names[i]], at + "." + names[i]);
      if (!g.contains("box")) r.fail(at, "needs a 'box': [[min x,y,z], [max x,y,z]]");
      auto box = r.vec_list<3>(g["box"], at + ".box");
      if (box.size() != 2) r.fail(at + ".box", "must be [[min x,y,z], [max x,y,z]]");
      q.box_min = box[0];
      q.box_max = box[1];
      q.material = material_ref(j, where);
      surf.geometry = q;
    } else if (kind == "bezier") {
      r.only_keys(j, where, {"bezier", "name", "material"});
      r.only_keys(g, at, {"points", "patches"});
      if (!g.contains("points") || !g.contains("patches")) r.fail(at, "needs 'points' and 'patches'");
      auto points = r.vec_list<3>(g["points"], at + ".points");
      const json& patches = g["patches"];
      if (!patches.is_array() || patches.empty()) r.fail(at + ".patches", "must be a non-empty array");
      bezier_surface b;
      for (std::size_t p = 0; p < patches.size(); ++p) {
        const std::string pw = at + ".patches[" + std::to_string(p) + "]";
        if (!patches[p].is_array() || patches[p].size() != 16) r.fail(pw, "must list 16 point indices");
        std::array<vec3, 16> control;
        for (int i = 0; i < 16; ++i) {
          int index = r.integer(patches[p][i], pw + "[" + std::to_string(i) + "]");
          if (index < 0 || index >= static_cast<int>(points.size()))
            r.fail(pw + "[" + std::to_string(i) + "]", "index " + std::to_string(index) + " is out of range");
          control[i] = points[index];
        }
        b.patches.push_back(control);
      }
      b.material = material_ref(j, where);
      surf.geometry = std::move(b);
    } else {  // bspline
      r.only_keys(j, where, {"bspline", "name", "material"});
      r.only_keys(g, at, {"rows", "cols", "points"});
      if (!g.contains("rows") || !g.contains("cols") || !g.contains("points"))
        r.fail(at, "needs 'rows', 'cols' and 'points'");
      bspline_surface b;
      b.rows = r.integer(g["rows"], at + ".rows");
      b.cols = r.integer(g["cols"], at + ".cols");
      if (b.rows < 4 || b.cols < 4 || b.rows > 4096 || b.cols > 4096)
        r.fail(at, "rows and cols must be from 4 to 4096");
      b.control = r.vec_list<3>(g["points"], at + ".points");
      if (b.control.size() != static_cast<std::size_t>(b.rows) * b.cols)
        r.fail(at + ".points", "needs rows*cols = " + std::to_string(b.rows * b.cols) + " points, got " +
                                   std::to_string(b.control.size()));
      b.material = material_ref(j, where);
      surf.geometry = std::move(b);
    }
    s.surfaces.push_back(std::move(surf));
  }

  void read(const json& doc) {
    r.only_keys(doc, "scene", {"camera", "background", "sky", "textures", "materials", "surfaces", "lights"});
    std::map<std::string, int> texture_by_name;
    if (doc.contains("textures")) {
      if (!doc["textures"].is_object()) r.fail("textures", "must be an object of name: texture");
      for (auto& [name, t] : doc["textures"].items()) {
        s.textures.push_back(read_texture(r, name, t));
        texture_by_name[name] = static_cast<int>(s.textures.size()) - 1;
      }
    }
    if (doc.contains("materials")) {
      if (!doc["materials"].is_object()) r.fail("materials", "must be an object of name: material");
      for (auto& [name, m] : doc["materials"].items()) {
        s.materials.push_back(read_material(r, name, m, texture_by_name));
        material_by_name[name] = static_cast<int>(s.materials.size()) - 1;
      }
    }
    if (!doc.contains("surfaces") || !doc["surfaces"].is_array() || doc["surfaces"].empty())
      r.fail("surfaces", "must be a non-empty array");
    const json& surfaces = doc["surfaces"];
    for (std::size_t i = 0; i < surfaces.size(); ++i) read_surface(surfaces[i], "surfaces[" + std::to_string(i) + "]");
    if (doc.contains("lights")) {
      if (!doc["lights"].is_array()) r.fail("lights", "must be an array");
      for (std::size_t i = 0; i < doc["lights"].size(); ++i) {
        const std::string where = "lights[" + std::to_string(i) + "]";
        const json& l = doc["lights"][i];
        r.only_keys(l, where, {"position", "intensity"});
        if (!l.contains("position") || !l.contains("intensity")) r.fail(where, "needs 'position' and 'intensity'");
        s.lights.push_back(
            {r.vec<3>(l["position"], where + ".position"), r.vec<3>(l["intensity"], where + ".intensity")});
      }
    }
    if (doc.contains("background")) s.background = r.vec<3>(doc["background"], "background");
    if (doc.contains("sky")) {
      // {"radiance": L} (uniform) or {"zenith": Lz, "horizon": Lh}, with an optional "up".
      const json& k = doc["sky"];
      r.only_keys(k, "sky", {"radiance", "zenith", "horizon", "up"});
      const bool uniform = k.contains("radiance");
      if (uniform == (k.contains("zenith") || k.contains("horizon")))
        r.fail("sky", "needs either 'radiance' (uniform) or 'zenith' and 'horizon' (a gradient)");
      if (uniform) {
        s.sky.zenith = s.sky.horizon = r.vec<3>(k["radiance"], "sky.radiance");
      } else {
        if (!k.contains("zenith") || !k.contains("horizon"))
          r.fail("sky", "a gradient needs both 'zenith' and 'horizon'");
        s.sky.zenith = r.vec<3>(k["zenith"], "sky.zenith");
        s.sky.horizon = r.vec<3>(k["horizon"], "sky.horizon");
      }
      if (k.contains("up")) s.sky.up = r.vec<3>(k["up"], "sky.up");
    }
    if (doc.contains("camera"))
      read_camera(r, doc["camera"], s.view);
    else
      s.view = fit_camera(s);
  }
};

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
  std::vector<bounds3> curved;  // boxes of curved surfaces: receivers seen from any side
  for (const surface& surf : s.surfaces) {
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

  for (const surface& surf : s.surfaces) {
    const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    if (!mesh) continue;
    bool emitting = false, reaches = false;
    std::string material_name;
    for (const face_ref& e : faces) {
      if (reaches) break;
      if (e.mesh != mesh || !emits(e.face->material)) continue;
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
      report.warnings = std::move(gltf.warnings);
      s.view = fit_camera(s);
    } else if (path.starts_with(generated_prefix)) {
      std::string error;
      if (!make_procedural_scene(std::string_view(path).substr(generated_prefix.size()), s, error))
        throw load_error(path + ": " + error);
      s.source = path;  // so that reopening it (the panel) builds it again
    } else if (ends_with_icase(path, ".json")) {
      std::optional<std::string> text = read_file(path);
      if (!text) throw load_error(path + ": cannot read file");
      json doc = parse_json(path, *text);
      scene_builder builder{json_reader{path}, s, report, {}};
      builder.read(doc);
    } else {
      throw load_error(path + ": unknown scene format (expected .json, .obj, .gltf, .glb or generated:NAME)");
    }
    drop_degenerate_faces(s, report);
    for (std::string& w : add_back_sides(s)) report.warnings.push_back(path + ": " + w);
    if (s.surfaces.empty()) throw load_error(path + ": no surfaces left after dropping degenerate faces");
    if (std::string problem = validate_scene(s); !problem.empty()) throw load_error(path + ": " + problem);
    const bool model_file =
        ends_with_icase(path, ".obj") || ends_with_icase(path, ".gltf") || ends_with_icase(path, ".glb");
    if (model_file && !has_light_source(s)) {
      // Most models come without lights: open them as a viewer would, under a white sky.
      s.sky.zenith = s.sky.horizon = rgb(1.0);
      report.warnings.push_back(path +
                                ": no emitter: lit by a uniform white sky of radiance 1 (a JSON scene with "
                                "\"sky\" or an emitter chooses the light)");
    }
    if (!has_light_source(s))
      report.warnings.push_back(path +
                                ": no emitter: no surface has a material with ke > 0 and there is no "
                                "point light, so nothing lights the scene");
    warn_unreachable_emitters(s, report);
  } catch (const load_error& e) {
    report.warnings.insert(report.warnings.end(), e.warnings.begin(), e.warnings.end());
    report.error = e.what();
    return false;
  } catch (const std::exception& e) {
    // Anything else (e.g. out of memory) still gets the file named.
    report.error = path + ": " + e.what();
    return false;
  }
  out = std::move(s);
  return true;
}

bool parse_camera_text(const std::string& text, const std::string& where, camera& cam, std::string& error) {
  try {
    const json doc = parse_json(where, text);
    const json_reader r{where};
    r.only_keys(doc, "camera file", {"camera"});
    if (!doc.contains("camera")) r.fail("camera file", "needs a 'camera' object");
    camera c = cam;
    read_camera(r, doc["camera"], c);
    cam = c;
    return true;
  } catch (const load_error& e) {
    error = e.what();
    return false;
  }
}

bool load_camera_file(const std::string& path, camera& cam, std::string& error) {
  const std::optional<std::string> text = read_file(path);
  if (!text) {
    error = path + ": cannot read file";
    return false;
  }
  return parse_camera_text(*text, path, cam, error);
}

std::string camera_json(const camera& cam) {
  const json doc = {{"camera",
                     {{"eye", {cam.eye.x, cam.eye.y, cam.eye.z}},
                      {"target", {cam.target.x, cam.target.y, cam.target.z}},
                      {"up", {cam.up.x, cam.up.y, cam.up.z}},
                      {"fov", cam.fov_y_degrees},
                      {"size", {cam.width, cam.height}}}}};
  return doc.dump(2) + "\n";
}

}  // namespace bounce
