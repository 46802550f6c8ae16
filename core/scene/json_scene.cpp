#include "scene/json_scene.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numbers>
#include <optional>

#include "scene/framing.h"
#include "scene/obj_io.h"

namespace bounce {
namespace {

using json = nlohmann::json;

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

}  // namespace

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
    throw load_error(path + ":" + line_column(text, e.byte == 0 ? 0 : e.byte - 1) +
                     ": invalid JSON: " + json_parse_reason(what));
  }
}

void read_camera(const json_reader& r, const json& j, camera& cam, bool partial) {
  r.only_keys(j, "camera", {"eye", "target", "up", "fov", "size"});
  if (!partial && (!j.contains("eye") || !j.contains("target"))) r.fail("camera", "needs 'eye' and 'target'");
  if (j.contains("eye")) cam.eye = r.vec<3>(j["eye"], "camera.eye");
  if (j.contains("target")) cam.target = r.vec<3>(j["target"], "camera.target");
  if (j.contains("up")) cam.up = r.vec<3>(j["up"], "camera.up");
  if (j.contains("fov")) cam.fov_y_degrees = r.number(j["fov"], "camera.fov");
  if (j.contains("size")) {
    const json& size = j["size"];
    if (!size.is_array() || size.size() != 2) r.fail("camera.size", "must be [width, height]");
    cam.width = r.integer(size[0], "camera.size[0]");
    cam.height = r.integer(size[1], "camera.size[1]");
  }
}

namespace {

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
  r.only_keys(
      j, where,
      {"rho", "ke", "kr", "kt", "ior", "fresnel", "specular", "shininess", "texture", "two_sided", "alpha_cutoff"});
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
  if (j.contains("alpha_cutoff")) {
    m.alpha_cutoff = r.number(j["alpha_cutoff"], where + ".alpha_cutoff");
    if (!(m.alpha_cutoff >= 0.0 && m.alpha_cutoff <= 1.0)) r.fail(where + ".alpha_cutoff", "must be from 0 to 1");
  }
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
  std::vector<std::string>& warnings;
  std::size_t& dropped_faces;
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
    dropped_faces += obj.dropped_faces;
    warnings.insert(warnings.end(), obj.warnings.begin(), obj.warnings.end());
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
      // As for OBJ faces: triangulating more corners costs too much.
      if (g.is_array() && g.size() > max_face_corners)
        r.fail(at, "has " + std::to_string(g.size()) + " corners; at most " + std::to_string(max_face_corners) +
                       " per polygon (split it, or give it as an OBJ with faces)");
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

  // {"position", "intensity"} (a point light), with "type": "spot" also
  // "direction" and the cones' half-angles "inner_cone_degrees" and
  // "outer_cone_degrees" (glTF's defaults 0 and 45); {"type": "sun",
  // "direction", "irradiance"}.
  punctual_light read_light(const json& l, const std::string& where) {
    punctual_light light;
    const std::string type = l.contains("type") ? r.string(l["type"], where + ".type") : "point";
    auto need = [&](std::initializer_list<const char*> keys) {
      for (const char* k : keys)
        if (!l.contains(k)) r.fail(where, std::string("a ") + type + " light needs '" + k + "'");
    };
    auto direction = [&] {
      const vec3 d = r.vec<3>(l["direction"], where + ".direction");
      if (!(glm::length(d) > 0.0) || !std::isfinite(glm::length(d)))
        r.fail(where + ".direction", "must be a finite, non-zero vector");
      return glm::normalize(d);
    };
    if (type == "point") {
      r.only_keys(l, where, {"type", "position", "intensity"});
      need({"position", "intensity"});
    } else if (type == "spot") {
      r.only_keys(l, where, {"type", "position", "intensity", "direction", "inner_cone_degrees", "outer_cone_degrees"});
      need({"position", "intensity", "direction"});
      light.type = light_type::spot;
      light.direction = direction();
      const double degree = std::numbers::pi / 180.0;
      if (l.contains("inner_cone_degrees"))
        light.inner_cone = r.number(l["inner_cone_degrees"], where + ".inner_cone_degrees") * degree;
      if (l.contains("outer_cone_degrees"))
        light.outer_cone = r.number(l["outer_cone_degrees"], where + ".outer_cone_degrees") * degree;
      if (!(light.inner_cone >= 0.0 && light.inner_cone < light.outer_cone && light.outer_cone <= 90.0 * degree))
        r.fail(where, "spot cones need 0 <= inner_cone_degrees < outer_cone_degrees <= 90");
    } else if (type == "sun") {
      r.only_keys(l, where, {"type", "direction", "irradiance"});
      need({"direction", "irradiance"});
      light.type = light_type::sun;
      light.direction = direction();
      light.intensity = r.vec<3>(l["irradiance"], where + ".irradiance");
      return light;
    } else {
      r.fail(where + ".type", "'" + type + "' is not a light type (point, spot or sun)");
    }
    light.position = r.vec<3>(l["position"], where + ".position");
    light.intensity = r.vec<3>(l["intensity"], where + ".intensity");
    return light;
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
        s.lights.push_back(read_light(doc["lights"][i], "lights[" + std::to_string(i) + "]"));
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

}  // namespace

void read_json_scene(const std::string& path, scene& s, std::vector<std::string>& warnings,
                     std::size_t& dropped_faces) {
  std::optional<std::string> text = read_file(path);
  if (!text) throw load_error(path + ": cannot read file");
  json doc = parse_json(path, *text);
  scene_builder builder{json_reader{path}, s, warnings, dropped_faces, {}};
  builder.read(doc);
}

}  // namespace bounce
