#include "obj_io.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string_view>

#include <stb/stb_image.h>

#include "scene_io.h"

namespace bounce {
namespace {

// Largest counts a text file may declare; past these the input is absurd for
// a radiosity scene and would only exhaust memory.
constexpr std::size_t max_obj_elements = 20'000'000;

std::string resolve(const std::string& base_file, const std::string& relative) {
  std::filesystem::path rel(relative);
  if (rel.is_absolute()) return relative;
  return (std::filesystem::path(base_file).parent_path() / rel).lexically_normal().string();
}

// Splits a line into whitespace-separated tokens (views into `line`).
std::vector<std::string_view> tokenize(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// Iterates a text file's lines with their numbers; strips comments and CR.
struct line_reader {
  std::string_view text;
  std::size_t pos = 0;
  int number = 0;

  bool next(std::string_view& line) {
    if (pos >= text.size()) return false;
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    line = text.substr(pos, end - pos);
    pos = end + 1;
    ++number;
    if (std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    return true;
  }
};

std::string at(const std::string& file, int line) {
  return file + ":" + std::to_string(line);
}

// Calls statement(tokens, "file:line", line) for every non-empty line of a
// Wavefront file (OBJ and MTL share this syntax).
template <typename callback>
void for_each_statement(std::string_view text, const std::string& path, callback&& statement) {
  line_reader lines{text};
  std::string_view line;
  while (lines.next(line)) {
    const auto tokens = tokenize(line);
    if (!tokens.empty()) statement(tokens, at(path, lines.number), lines.number);
  }
}

double parse_number(std::string_view token, const std::string& where) {
  double value = 0.0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    throw load_error(where + ": '" + std::string(token) + "' is not a number");
  if (!std::isfinite(value)) throw load_error(where + ": '" + std::string(token) + "' is not a finite number");
  return value;
}

// Reads `count` numbers starting at tokens[1]; `optional_extra` more may follow.
std::vector<double> parse_numbers(const std::vector<std::string_view>& tokens, std::size_t count,
                                  std::size_t optional_extra, const std::string& where) {
  std::size_t given = tokens.size() - 1;
  if (given < count || given > count + optional_extra) {
    std::ostringstream msg;
    msg << where << ": '" << tokens[0] << "' needs " << count;
    if (optional_extra) msg << " to " << count + optional_extra;
    msg << " numbers, got " << given;
    throw load_error(msg.str());
  }
  std::vector<double> values;
  for (std::size_t i = 1; i < tokens.size(); ++i) values.push_back(parse_number(tokens[i], where));
  return values;
}

// A colour statement: one value (grey) or three.
rgb parse_colour(const std::vector<std::string_view>& tokens, const std::string& where) {
  if (tokens.size() == 2) return rgb(parse_number(tokens[1], where));
  auto v = parse_numbers(tokens, 3, 0, where);
  return rgb(v[0], v[1], v[2]);
}

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// What an MTL block says, before it is turned into a material.
struct mtl_block {
  material mat;
  rgb ks{0.0};
  double dissolve = 1.0;
  int illum = 1;
  int line = 0;
};

// MTL illumination models (Wavefront spec): 2 adds the highlight, 3 and up
// ray-traced reflection, 4/6/7/9 transparency, 5 and 7 Fresnel.
material finish_material(const mtl_block& b) {
  material m = b.mat;
  if (b.illum >= 2) m.specular = b.ks;
  if (b.illum >= 3) m.kr = b.ks;
  if (b.illum == 5 || b.illum == 7) m.fresnel = true;
  m.kt = rgb(1.0 - b.dissolve);
  return m;
}

void read_mtl(const std::string& path, const std::string& where, std::vector<material>& materials,
              std::vector<texture>& textures, std::map<std::string, int>& by_name, std::vector<std::string>& warnings) {
  std::optional<std::string> text = read_file(path);
  if (!text) throw load_error(where + ": cannot read material library '" + path + "'");

  std::vector<mtl_block> blocks;
  std::set<std::string> ignored;
  for_each_statement(*text, path,
                     [&](const std::vector<std::string_view>& tokens, const std::string& here, int number) {
                       const std::string_view key = tokens[0];
                       if (key == "newmtl") {
                         if (tokens.size() != 2) throw load_error(here + ": 'newmtl' needs one name");
                         blocks.push_back({});
                         blocks.back().mat.name = std::string(tokens[1]);
                         blocks.back().line = number;
                         return;
                       }
                       if (blocks.empty()) throw load_error(here + ": '" + std::string(key) + "' before any 'newmtl'");
                       mtl_block& b = blocks.back();
                       if (key == "Kd")
                         b.mat.rho = parse_colour(tokens, here);
                       else if (key == "Ke")
                         b.mat.ke = parse_colour(tokens, here);
                       else if (key == "Ks")
                         b.ks = parse_colour(tokens, here);
                       else if (key == "Ns")
                         b.mat.shininess = parse_numbers(tokens, 1, 0, here)[0];
                       else if (key == "Ni")
                         b.mat.ior = parse_numbers(tokens, 1, 0, here)[0];
                       else if (key == "d")
                         b.dissolve = parse_numbers(tokens, 1, 0, here)[0];
                       else if (key == "Tr")
                         b.dissolve = 1.0 - parse_numbers(tokens, 1, 0, here)[0];
                       else if (key == "illum") {
                         double v = parse_numbers(tokens, 1, 0, here)[0];
                         if (v != std::floor(v) || v < 0 || v > 10)
                           throw load_error(here + ": 'illum' must be an integer from 0 to 10");
                         b.illum = static_cast<int>(v);
                       } else if (key == "map_Kd") {
                         // Options such as "-s 1 1 1" may precede the file name, which comes last.
                         if (tokens.size() < 2) throw load_error(here + ": 'map_Kd' needs a file name");
                         std::string name(tokens.back());
                         textures.push_back(read_image_texture(resolve(path, name), name, here));
                         b.mat.texture = static_cast<int>(textures.size()) - 1;
                       } else if (ignored.insert(std::string(key)).second) {
                         warnings.push_back(here + ": '" + std::string(key) + "' is not used by Bounce; ignored");
                       }
                     });
  for (const mtl_block& b : blocks) {
    if (b.dissolve < 0.0 || b.dissolve > 1.0)
      throw load_error(at(path, b.line) + ": material '" + b.mat.name + "': d must be in [0,1]");
    if (by_name.count(b.mat.name))
      warnings.push_back(at(path, b.line) + ": material '" + b.mat.name +
                         "' defined again; the first definition is used");
    else {
      materials.push_back(finish_material(b));
      by_name[b.mat.name] = static_cast<int>(materials.size()) - 1;
    }
  }
}

// Turns an OBJ index (1-based, or negative = relative to the end) into a
// 0-based one, or throws naming the line.
int resolve_index(std::string_view token, std::size_t count, const char* what, const std::string& where) {
  long value = 0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    throw load_error(where + ": bad " + what + " index '" + std::string(token) + "'");
  long index = value > 0 ? value - 1 : static_cast<long>(count) + value;
  if (value == 0 || index < 0 || index >= static_cast<long>(count))
    throw load_error(where + ": " + what + " index " + std::string(token) + " is out of range (" +
                     std::to_string(count) + " defined so far)");
  return static_cast<int>(index);
}

// Collects one `o` object; vertices are renumbered to the object's own arrays.
struct object_builder {
  surface out;
  std::map<int, int> position_map, normal_map, uv_map;

  static int remap(std::map<int, int>& map, int global, auto& dest, const auto& source) {
    auto [it, inserted] = map.try_emplace(global, static_cast<int>(dest.size()));
    if (inserted) dest.push_back(source[global]);
    return it->second;
  }
};

}  // namespace

texture read_image_texture(const std::string& path, const std::string& name, const std::string& where) {
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) throw load_error(where + ": cannot read texture '" + path + "'");
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes->data()),
                                                static_cast<int>(bytes->size()), &w, &h, &channels, 3);
  if (!pixels) throw load_error(where + ": cannot decode texture '" + path + "': " + stbi_failure_reason());
  texture t;
  t.name = name;
  t.kind = texture_kind::image;
  t.width = w;
  t.height = h;
  t.texels.resize(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < t.texels.size(); ++i) t.texels[i] = static_cast<float>(srgb_to_linear(pixels[i] / 255.0));
  stbi_image_free(pixels);
  return t;
}

obj_read_result read_obj(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures) {
  std::optional<std::string> text = read_file(path);
  if (!text) throw load_error(path + ": cannot read file");

  obj_read_result result;
  std::vector<vec3> positions, normals;
  std::vector<vec2> uvs;
  std::map<std::string, int> material_by_name;
  std::vector<object_builder> objects;
  std::set<std::string> ignored;
  int current_material = -1;
  int default_material = -1;

  auto current_object = [&]() -> object_builder& {
    if (objects.empty()) {
      objects.emplace_back();
      objects.back().out.name = std::filesystem::path(path).stem().string();
      objects.back().out.source = path;
      objects.back().out.geometry = polygon_mesh{};
    }
    return objects.back();
  };

  for_each_statement(
      *text, path, [&](const std::vector<std::string_view>& tokens, const std::string& here, int number) {
        const std::string_view key = tokens[0];
        if (positions.size() + normals.size() + uvs.size() > max_obj_elements)
          throw load_error(here + ": more than " + std::to_string(max_obj_elements) +
                           " vertices; too large for Bounce");
        if (key == "v") {
          auto v = parse_numbers(tokens, 3, 1, here);  // optional w is ignored
          positions.emplace_back(v[0], v[1], v[2]);
        } else if (key == "vn") {
          auto v = parse_numbers(tokens, 3, 0, here);
          vec3 n(v[0], v[1], v[2]);
          if (glm::length(n) == 0.0) throw load_error(here + ": normal has zero length");
          normals.push_back(glm::normalize(n));
        } else if (key == "vt") {
          auto v = parse_numbers(tokens, 1, 2, here);
          uvs.emplace_back(v[0], v.size() > 1 ? v[1] : 0.0);
        } else if (key == "f") {
          if (current_material < 0) {
            if (default_material < 0) {
              material grey;
              grey.name = "default";
              grey.rho = rgb(0.5);
              materials.push_back(grey);
              default_material = static_cast<int>(materials.size()) - 1;
              result.warnings.push_back(here + ": faces without 'usemtl' get a grey default material");
            }
            current_material = default_material;
          }
          object_builder& obj = current_object();
          auto& mesh = std::get<polygon_mesh>(obj.out.geometry);
          polygon_face face;
          face.material = current_material;
          face.line = number;
          std::size_t with_uv = 0, with_normal = 0;
          for (std::size_t i = 1; i < tokens.size(); ++i) {
            // v, v/vt, v//vn or v/vt/vn
            std::string_view corner = tokens[i];
            std::size_t s1 = corner.find('/');
            std::string_view pv = corner.substr(0, s1), tv, nv;
            if (s1 != std::string_view::npos) {
              std::size_t s2 = corner.find('/', s1 + 1);
              tv = corner.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
              if (s2 != std::string_view::npos) nv = corner.substr(s2 + 1);
            }
            int p = resolve_index(pv, positions.size(), "vertex", here);
            face.position.push_back(object_builder::remap(obj.position_map, p, mesh.positions, positions));
            if (!tv.empty()) {
              int t = resolve_index(tv, uvs.size(), "texture coordinate", here);
              face.uv.push_back(object_builder::remap(obj.uv_map, t, mesh.uvs, uvs));
              ++with_uv;
            }
            if (!nv.empty()) {
              int n = resolve_index(nv, normals.size(), "normal", here);
              face.normal.push_back(object_builder::remap(obj.normal_map, n, mesh.normals, normals));
              ++with_normal;
            }
          }
          const std::size_t corners = face.position.size();
          if ((with_uv != 0 && with_uv != corners) || (with_normal != 0 && with_normal != corners))
            throw load_error(here + ": every corner of a face must have the same form (v, v/vt, v//vn, v/vt/vn)");
          if (corners < 3) {
            ++result.dropped_faces;
            result.warnings.push_back(here + ": face with " + std::to_string(corners) + " corners dropped");
            return;
          }
          mesh.faces.push_back(std::move(face));
        } else if (key == "o") {
          objects.emplace_back();
          objects.back().out.name =
              tokens.size() > 1 ? std::string(tokens[1]) : "object" + std::to_string(objects.size());
          objects.back().out.source = path;
          objects.back().out.geometry = polygon_mesh{};
        } else if (key == "usemtl") {
          if (tokens.size() != 2) throw load_error(here + ": 'usemtl' needs one name");
          auto it = material_by_name.find(std::string(tokens[1]));
          if (it == material_by_name.end())
            throw load_error(here + ": material '" + std::string(tokens[1]) +
                             "' is not defined in any mtllib read so far");
          current_material = it->second;
        } else if (key == "mtllib") {
          if (tokens.size() < 2) throw load_error(here + ": 'mtllib' needs a file name");
          for (std::size_t i = 1; i < tokens.size(); ++i)
            read_mtl(resolve(path, std::string(tokens[i])), here, materials, textures, material_by_name,
                     result.warnings);
        } else if (key == "g" || key == "s") {
          // Groups and smoothing groups carry nothing Bounce uses: smoothness
          // comes from the normals given or from the faces' planes.
        } else if (ignored.insert(std::string(key)).second) {
          result.warnings.push_back(here + ": '" + std::string(key) + "' is not used by Bounce; ignored");
        }
      });

  for (object_builder& obj : objects)
    if (!std::get<polygon_mesh>(obj.out.geometry).faces.empty()) result.surfaces.push_back(std::move(obj.out));
  if (result.surfaces.empty()) throw load_error(path + ": no faces");
  return result;
}

}  // namespace bounce
