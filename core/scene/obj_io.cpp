#include "scene/obj_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "scene/reader_support.h"

namespace bounce {
namespace {

// Largest counts a text file may declare; past these the input is absurd for
// a radiosity scene and would only exhaust memory.
constexpr std::size_t max_obj_elements = 20'000'000;
constexpr const char* default_material_text = "the grey default material (rho 0.5)";

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

// The text of a statement from tokens[first] to the end of the line, inner
// spaces kept: material and file names may contain spaces.
std::string rest_of(const std::vector<std::string_view>& tokens, std::size_t first) {
  if (first >= tokens.size()) return {};
  const char* begin = tokens[first].data();
  const char* end = tokens.back().data() + tokens.back().size();
  return std::string(begin, end);
}

// Iterates a text file's lines with their numbers; strips comments. Lines
// end in LF, CR LF or a lone CR (old Mac exporters still write those).
struct line_reader {
  std::string_view text;
  std::size_t pos = 0;
  int number = 0;

  bool next(std::string_view& line) {
    if (pos >= text.size()) return false;
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    line = text.substr(pos, end - pos);
    pos = end + (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? 2 : 1);
    ++number;
    if (std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
    return true;
  }
};

std::string at(const std::string& file, int line) {
  return file + ":" + std::to_string(line);
}

// The text of a file, refusing UTF-16 by name and skipping a UTF-8 byte
// order mark (Windows editors write both; the statements are ASCII).
std::string_view text_of(const std::string& bytes, const std::string& path) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(bytes[i]); };
  bool utf16 = bytes.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF));
  // Without a mark, ASCII saved as UTF-16 has a NUL in every other byte.
  const std::size_t probe = std::min<std::size_t>(bytes.size(), 4096);
  std::size_t nul_even = 0, nul_odd = 0;
  for (std::size_t i = 0; i < probe; ++i)
    if (bytes[i] == '\0') ++(i % 2 ? nul_odd : nul_even);
  if (probe >= 4 && std::max(nul_even, nul_odd) * 4 >= probe) utf16 = true;
  if (utf16) throw load_error(path + ": UTF-16 text; save it as UTF-8");
  if (bytes.find('\0') != std::string::npos) throw load_error(path + ": binary data (NUL bytes); not a text file");
  std::string_view text = bytes;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text;
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
  // from_chars has no leading '+'; accept it as strtod does ("+1", "+2.e1").
  std::string_view digits = token;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '+' && digits[1] != '-') digits.remove_prefix(1);
  double value = 0.0;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range)
    throw load_error(where + ": '" + std::string(token) + "' is out of range (limit " + format_value(max_file_number) +
                     ")");
  if (ec != std::errc() || end != digits.data() + digits.size())
    throw load_error(where + ": '" + std::string(token) + "' is not a number");
  if (!std::isfinite(value)) throw load_error(where + ": '" + std::string(token) + "' is not a finite number");
  if (std::abs(value) > max_file_number)
    throw load_error(where + ": " + std::string(token) +
                     " is out of range (numbers in OBJ and MTL files are limited to " + format_value(max_file_number) +
                     " in magnitude)");
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

// A colour statement: one value (grey) or three, none negative.
rgb parse_colour(const std::vector<std::string_view>& tokens, const std::string& where) {
  rgb c;
  if (tokens.size() == 2) {
    c = rgb(parse_number(tokens[1], where));
  } else {
    auto v = parse_numbers(tokens, 3, 0, where);
    c = rgb(v[0], v[1], v[2]);
  }
  if (glm::any(glm::lessThan(c, rgb(0.0))))
    throw load_error(where + ": '" + std::string(tokens[0]) + "' colour " + format_value(c) + " is negative");
  return c;
}

// A colour used as a reflectance: refused above max_colour_channel (the
// intent is unclear), channels of 1 or more clamped to max_reflectance.
// Returns whether it clamped.
bool clamp_reflectance(rgb& c, const std::string& what, const std::string& where) {
  if (glm::any(glm::greaterThan(c, rgb(max_colour_channel))))
    throw load_error(where + ": " + what + " " + format_value(c) + " is not a reflectance (channels go from 0 to 1)");
  bool clamped = false;
  for (int i = 0; i < 3; ++i)
    if (c[i] >= 1.0) {
      c[i] = max_reflectance;
      clamped = true;
    }
  return clamped;
}

// File names written on Windows: backslashes are separators.
std::string portable_name(std::string name, const std::string& where, std::set<std::string>& said,
                          std::vector<std::string>& warnings) {
  if (name.find('\\') == std::string::npos) return name;
  std::replace(name.begin(), name.end(), '\\', '/');
  if (said.insert("backslash").second)
    warnings.push_back(where + ": backslashes in file names read as '/' (Windows paths)");
  return name;
}

bool readable(const std::string& path) {
  if (path.rfind("embedded:", 0) == 0) return read_file(path).has_value();
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

// `path` itself or, on disk, a file in the same folder whose name differs
// only in case (files made on Windows and macOS disagree on case).
std::optional<std::string> find_file(const std::string& path) {
  if (readable(path)) return path;
  if (path.rfind("embedded:", 0) == 0) return std::nullopt;
  const std::filesystem::path p(path);
  std::error_code ec;
  const std::filesystem::path dir = p.parent_path().empty() ? "." : p.parent_path();
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  const std::string want = lower(p.filename().string());
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (lower(entry.path().filename().string()) == want && entry.is_regular_file(ec)) return entry.path().string();
  return std::nullopt;
}

// The file name of a map_Kd statement: options ("-s 1 1 1", "-clamp on")
// come first, and the name is the rest of the line (it may contain spaces).
std::string map_file_name(const std::vector<std::string_view>& tokens, const std::string& where) {
  static const std::map<std::string_view, int> fixed_arguments = {
      {"-blendu", 1},  {"-blendv", 1}, {"-bm", 1},     {"-boost", 1}, {"-cc", 1},        {"-clamp", 1},
      {"-imfchan", 1}, {"-mm", 2},     {"-texres", 1}, {"-type", 1},  {"-colorspace", 1}};
  std::size_t i = 1;
  while (i < tokens.size() && tokens[i].size() > 1 && tokens[i][0] == '-') {
    const std::string_view option = tokens[i++];
    if (auto it = fixed_arguments.find(option); it != fixed_arguments.end()) {
      i += it->second;
    } else if (option == "-o" || option == "-s" || option == "-t") {
      // One to three numbers.
      for (int k = 0; k < 3 && i < tokens.size(); ++k, ++i) {
        double v;
        auto [end, ec] = std::from_chars(tokens[i].data(), tokens[i].data() + tokens[i].size(), v);
        if (ec != std::errc() || end != tokens[i].data() + tokens[i].size()) break;
      }
    } else {
      break;  // not an option: a file name starting with '-'
    }
  }
  if (i >= tokens.size()) throw load_error(where + ": '" + std::string(tokens[0]) + "' needs a file name");
  return rest_of(tokens, i);
}

// What an MTL block says, before it is turned into a material; the lines
// of its statements, for messages.
struct mtl_block {
  material mat;
  rgb ks{0.0};
  double dissolve = 1.0;
  int illum = 1;
  int line = 0, kd_line = 0, ks_line = 0, d_line = 0, ni_line = 0, illum_line = 0;
  std::string d_statement;  // "d 0" or "Tr 1", as written
};

// MTL illumination models (Wavefront spec): 2 adds the highlight, 3 and up
// ray-traced reflection, 4/6/7/9 transparency, 5 and 7 Fresnel. Dissolve d
// mixes the material with nothing: a fraction d of the light meets the
// material (rho and kr scale by d), 1 - d passes through (kt). Reflectances
// that would create energy are clamped, with a warning naming the lines.
material finish_material(const mtl_block& b, const std::string& path, std::vector<std::string>& warnings) {
  material m = b.mat;
  const std::string who = "material '" + m.name + "'";
  if (b.illum >= 2) m.specular = b.ks;
  if (b.illum >= 3) m.kr = b.ks;
  if (b.illum == 5 || b.illum == 7) m.fresnel = true;
  if (b.illum >= 3 && glm::any(glm::greaterThan(m.kr, rgb(max_colour_channel))))
    throw load_error(at(path, b.ks_line) + ": Ks " + format_value(b.ks) + " of " + who +
                     " (a mirror reflectance with illum " + std::to_string(b.illum) +
                     ") is not a reflectance (channels go from 0 to 1)");
  const rgb kd = m.rho;
  if (clamp_reflectance(m.rho, "Kd", at(path, b.kd_line)))
    warnings.push_back(at(path, b.kd_line) + ": Kd " + format_value(kd) + " of " + who + " clamped to " +
                       format_value(m.rho) + " (a reflectance of 1 or more would create energy)");
  m.rho *= b.dissolve;
  m.kr *= b.dissolve;
  m.kt = rgb(1.0 - b.dissolve);
  if (b.dissolve == 0.0)
    warnings.push_back(at(path, b.d_line) + ": '" + b.d_statement + "' makes " + who +
                       " fully transparent: its faces are invisible");
  const rgb sum = m.rho + m.kr + m.kt;
  const double most = std::max({sum.r, sum.g, sum.b});
  if (most > 1.0) {
    const double scale = max_reflectance / most;
    m.rho *= scale;
    m.kr *= scale;
    m.kt *= scale;
    std::string lines = "Kd at line " + std::to_string(b.kd_line);
    if (b.ks_line) lines += ", Ks at line " + std::to_string(b.ks_line) + " with illum " + std::to_string(b.illum);
    if (b.d_line) lines += ", " + b.d_statement + " at line " + std::to_string(b.d_line);
    warnings.push_back(at(path, b.line) + ": " + who +
                       " reflects more than it receives (rho + kr + kt = " + format_value(most) + "; " + lines +
                       "); all three scaled by " + format_value(scale) + " to sum to " + format_value(max_reflectance));
  }
  if (m.ior <= 0.0) {
    if (m.kt != rgb(0.0) || m.fresnel)
      throw load_error(at(path, b.ni_line) + ": Ni " + format_value(m.ior) + " of " + who +
                       " is not a refractive index (it must be positive for a transparent or Fresnel material)");
    warnings.push_back(at(path, b.ni_line) + ": Ni " + format_value(m.ior) + " of " + who +
                       " is not a refractive index; ignored (the material is opaque)");
    m.ior = 1.0;
  }
  return m;
}

struct library_state {
  std::map<std::string, int> by_name;  // material name -> scene index
  std::set<std::string> read;          // libraries already read
  std::set<std::string> said;          // one-per-file warnings already given
};

void read_mtl(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures,
              library_state& libs, std::vector<std::string>& warnings) {
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) throw load_error(path + ": cannot read file");
  const std::string_view text = text_of(*bytes, path);

  std::vector<mtl_block> blocks;
  std::set<std::string> ignored;
  std::set<std::string> said;
  for_each_statement(text, path, [&](const std::vector<std::string_view>& tokens, const std::string& here, int number) {
    const std::string_view key = tokens[0];
    if (key == "newmtl") {
      // The name is the rest of the line: names may contain spaces, and
      // Blender writes an empty name for an unnamed material.
      blocks.push_back({});
      blocks.back().mat.name = rest_of(tokens, 1);
      blocks.back().line = number;
      return;
    }
    if (blocks.empty()) throw load_error(here + ": '" + std::string(key) + "' before any 'newmtl'");
    mtl_block& b = blocks.back();
    if (key == "Kd") {
      b.mat.rho = parse_colour(tokens, here);
      b.kd_line = number;
    } else if (key == "Ke") {
      b.mat.ke = parse_colour(tokens, here);
    } else if (key == "Ks") {
      b.ks = parse_colour(tokens, here);
      b.ks_line = number;
    } else if (key == "Ns") {
      b.mat.shininess = parse_numbers(tokens, 1, 0, here)[0];
      if (b.mat.shininess < 0.0) throw load_error(here + ": 'Ns' must not be negative");
    } else if (key == "Ni") {
      b.mat.ior = parse_numbers(tokens, 1, 0, here)[0];
      b.ni_line = number;
    } else if (key == "d" || key == "Tr") {
      const double v = parse_numbers(tokens, 1, 0, here)[0];
      if (v < 0.0 || v > 1.0) throw load_error(here + ": '" + std::string(key) + "' must be from 0 to 1");
      b.dissolve = key == "d" ? v : 1.0 - v;
      b.d_line = number;
      b.d_statement = std::string(key) + " " + std::string(tokens[1]);
    } else if (key == "illum") {
      double v = parse_numbers(tokens, 1, 0, here)[0];
      if (v != std::floor(v) || v < 0 || v > 10) throw load_error(here + ": 'illum' must be an integer from 0 to 10");
      b.illum = static_cast<int>(v);
      b.illum_line = number;
    } else if (key == "map_Kd") {
      const std::string name = portable_name(map_file_name(tokens, here), here, said, warnings);
      const std::string wanted = resolve(path, name);
      const std::optional<std::string> found = find_file(wanted);
      if (found && *found != wanted)
        warnings.push_back(here + ": texture '" + name + "' not found; using '" + *found +
                           "' (same name but for case)");
      textures.push_back(read_image_texture(found.value_or(wanted), name, here));
      b.mat.texture = static_cast<int>(textures.size()) - 1;
    } else if (ignored.insert(std::string(key)).second) {
      warnings.push_back(here + ": '" + std::string(key) + "' is not used by Bounce; ignored");
    }
  });
  for (const mtl_block& b : blocks) {
    if (libs.by_name.count(b.mat.name)) {
      warnings.push_back(at(path, b.line) + ": material '" + b.mat.name +
                         "' defined again; the first definition is used");
    } else {
      materials.push_back(finish_material(b, path, warnings));
      libs.by_name[b.mat.name] = static_cast<int>(materials.size()) - 1;
    }
  }
}

// An `mtllib` statement: one or more library names, or one name with
// spaces. A library that cannot be found is a warning (its materials then
// get the default); one whose name is off by case or extension is read.
void read_mtllib(const std::vector<std::string_view>& tokens, const std::string& obj_path, const std::string& here,
                 std::vector<material>& materials, std::vector<texture>& textures, library_state& libs,
                 std::vector<std::string>& warnings) {
  if (tokens.size() < 2) throw load_error(here + ": 'mtllib' needs a file name");
  std::vector<std::string> names;
  const std::string whole = portable_name(rest_of(tokens, 1), here, libs.said, warnings);
  if (tokens.size() > 2 && find_file(resolve(obj_path, whole)))
    names.push_back(whole);
  else
    for (std::size_t i = 1; i < tokens.size(); ++i)
      names.push_back(portable_name(std::string(tokens[i]), here, libs.said, warnings));
  for (const std::string& name : names) {
    const std::string wanted = resolve(obj_path, name);
    std::optional<std::string> found = find_file(wanted);
    if (!found) {
      // Exporters rename one file but not the other: try name.mtl, then the
      // OBJ's own name with .mtl.
      for (std::filesystem::path alt : {std::filesystem::path(wanted).replace_extension(".mtl"),
                                        std::filesystem::path(obj_path).replace_extension(".mtl")})
        if (!found && alt.string() != obj_path) found = find_file(alt.string());
    }
    if (!found) {
      warnings.push_back(here + ": cannot read material library '" + wanted + "'; its materials get " +
                         default_material_text);
      continue;
    }
    if (*found != wanted)
      warnings.push_back(here + ": material library '" + name + "' not found; reading '" + *found + "' instead");
    if (!libs.read.insert(*found).second) continue;
    read_mtl(*found, materials, textures, libs, warnings);
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
// Faces hold a material *name* id until every mtllib has been read.
struct object_builder {
  surface out;
  std::map<int, int> position_map, normal_map, uv_map;
  std::vector<std::optional<rgb>> face_colour;  // mean vertex colour, per face

  static int remap(std::map<int, int>& map, int global, auto& dest, const auto& source) {
    auto [it, inserted] = map.try_emplace(global, static_cast<int>(dest.size()));
    if (inserted) dest.push_back(source[global]);
    return it->second;
  }
};

// A unit vector along v, scaled first so that its length cannot overflow.
vec3 normalized(const vec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest > 0.0 ? glm::normalize(v / largest) : vec3(0.0);
}

void read_obj_statements(const std::string& path, const std::string_view text, std::vector<material>& materials,
                         std::vector<texture>& textures, obj_read_result& result) {
  std::vector<vec3> positions, normals;
  std::vector<vec2> uvs;
  std::vector<std::optional<rgb>> colours;  // per position: `v x y z r g b`
  library_state libs;
  std::vector<object_builder> objects;
  std::set<std::string> ignored;
  std::map<std::string, int> ignored_count;
  // usemtl names in order of first use, with the line of that use.
  std::vector<std::pair<std::string, int>> used_names;
  std::map<std::string, int> name_id;
  int current_name = -1;
  int first_face_without_usemtl = 0, first_clamped_colour = 0, first_zero_normal = 0;

  auto new_object = [&](std::string name) {
    objects.emplace_back();
    objects.back().out.name = std::move(name);
    objects.back().out.source = path;
    objects.back().out.geometry = polygon_mesh{};
  };

  for_each_statement(text, path, [&](const std::vector<std::string_view>& tokens, const std::string& here, int number) {
    const std::string_view key = tokens[0];
    if (positions.size() + normals.size() + uvs.size() > max_obj_elements)
      throw load_error(here + ": more than " + std::to_string(max_obj_elements) + " vertices; too large for Bounce");
    if (key == "v") {
      // x y z, x y z w (w ignored) or x y z r g b (a vertex colour).
      if (tokens.size() == 8)
        throw load_error(here + ": 'v' with 7 numbers is ambiguous (x y z w r g b or x y z r g b a?)");
      auto v = parse_numbers(tokens, 3, 3, here);
      if (v.size() == 5) throw load_error(here + ": 'v' needs 3, 4 or 6 numbers, got 5");
      positions.emplace_back(v[0], v[1], v[2]);
      colours.emplace_back();
      if (v.size() == 6) {
        rgb c(v[3], v[4], v[5]);
        if (glm::any(glm::lessThan(c, rgb(0.0))))
          throw load_error(here + ": vertex colour " + format_value(c) + " is negative");
        if (clamp_reflectance(c, "vertex colour", here) && !first_clamped_colour) first_clamped_colour = number;
        colours.back() = c;
      }
    } else if (key == "vn") {
      auto v = parse_numbers(tokens, 3, 0, here);
      vec3 n(v[0], v[1], v[2]);
      // A zero normal says nothing: corners using it get the face's normal
      // (exporters write 'vn 0 0 0' for degenerate faces).
      if (n == vec3(0.0) && !first_zero_normal) first_zero_normal = number;
      normals.push_back(normalized(n));
    } else if (key == "vt") {
      auto v = parse_numbers(tokens, 1, 2, here);
      uvs.emplace_back(v[0], v.size() > 1 ? v[1] : 0.0);
    } else if (key == "f") {
      if (tokens.size() - 1 > max_face_corners)
        throw load_error(here + ": face with " + std::to_string(tokens.size() - 1) + " corners; Bounce takes at most " +
                         std::to_string(max_face_corners) + " per face");
      if (current_name < 0 && !first_face_without_usemtl) first_face_without_usemtl = number;
      if (objects.empty()) new_object(std::filesystem::path(path).stem().string());
      object_builder& obj = objects.back();
      auto& mesh = std::get<polygon_mesh>(obj.out.geometry);
      polygon_face face;
      face.material = current_name;
      face.line = number;
      std::size_t with_uv = 0, with_normal = 0, with_colour = 0;
      rgb colour_sum(0.0);
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
        if (colours[p]) {
          colour_sum += *colours[p];
          ++with_colour;
        }
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
      obj.face_colour.push_back(with_colour == corners ? std::optional<rgb>(colour_sum / double(corners))
                                                       : std::nullopt);
    } else if (key == "o") {
      new_object(tokens.size() > 1 ? rest_of(tokens, 1) : "object" + std::to_string(objects.size() + 1));
    } else if (key == "usemtl") {
      // The name is the rest of the line (names may contain spaces; Blender
      // writes an empty one). It is looked up once every mtllib is read.
      const std::string name = rest_of(tokens, 1);
      auto [it, fresh] = name_id.try_emplace(name, static_cast<int>(used_names.size()));
      if (fresh) used_names.emplace_back(name, number);
      current_name = it->second;
    } else if (key == "mtllib") {
      read_mtllib(tokens, path, here, materials, textures, libs, result.warnings);
    } else if (key == "g" || key == "s") {
      // Groups and smoothing groups carry nothing Bounce uses: smoothness
      // comes from the normals given or from the faces' planes.
    } else {
      ++ignored_count[std::string(key)];
      if (ignored.insert(std::string(key)).second)
        result.warnings.push_back(here + ": '" + std::string(key) + "' is not used by Bounce; ignored");
    }
  });

  // Materials by name, now that every library is read; faces without one
  // take their vertex colours or the grey default.
  std::vector<int> material_of_name(used_names.size(), -1);
  std::vector<bool> name_faces_coloured(used_names.size(), true), name_has_faces(used_names.size(), false);
  for (std::size_t i = 0; i < used_names.size(); ++i)
    if (auto it = libs.by_name.find(used_names[i].first); it != libs.by_name.end()) material_of_name[i] = it->second;
  int default_material = -1;
  std::map<std::array<int, 3>, int> colour_material;
  int first_coloured_face = 0;
  bool default_without_usemtl = false;
  for (object_builder& obj : objects) {
    auto& mesh = std::get<polygon_mesh>(obj.out.geometry);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      polygon_face& face = mesh.faces[f];
      const int name = face.material;
      if (name >= 0) name_has_faces[name] = true;
      if (name >= 0 && material_of_name[name] >= 0) {
        face.material = material_of_name[name];
        continue;
      }
      if (name >= 0 && !obj.face_colour[f]) name_faces_coloured[name] = false;
      if (const auto& c = obj.face_colour[f]) {
        // One material per distinct colour, to 1/255 (what 8-bit exporters write).
        const std::array<int, 3> key{static_cast<int>(std::lround(c->r * 255)),
                                     static_cast<int>(std::lround(c->g * 255)),
                                     static_cast<int>(std::lround(c->b * 255))};
        auto [it, fresh] = colour_material.try_emplace(key, 0);
        if (fresh) {
          material m;
          m.name =
              "vertex colour " + std::to_string(key[0]) + " " + std::to_string(key[1]) + " " + std::to_string(key[2]);
          m.rho = glm::min(rgb(key[0], key[1], key[2]) / 255.0, rgb(max_reflectance));
          materials.push_back(m);
          it->second = static_cast<int>(materials.size()) - 1;
        }
        face.material = it->second;
        if (!first_coloured_face) first_coloured_face = face.line;
        continue;
      }
      if (default_material < 0) {
        material grey;
        grey.name = "default";
        grey.rho = rgb(0.5);
        materials.push_back(grey);
        default_material = static_cast<int>(materials.size()) - 1;
      }
      if (name < 0) default_without_usemtl = true;
      face.material = default_material;
    }
  }
  if (first_zero_normal)
    result.warnings.push_back(at(path, first_zero_normal) +
                              ": zero-length normals ('vn 0 0 0'); corners using them get their face's normal");
  if (first_clamped_colour)
    result.warnings.push_back(at(path, first_clamped_colour) + ": vertex colour channels of 1 or more clamped to " +
                              format_value(max_reflectance) + " (a reflectance of 1 or more would create energy)");
  if (first_coloured_face)
    result.warnings.push_back(at(path, first_coloured_face) +
                              ": faces without a material take their vertex colours (mean of the corners) as rho");
  if (default_without_usemtl)
    result.warnings.push_back(at(path, first_face_without_usemtl) + ": faces without 'usemtl' get " +
                              default_material_text);
  for (std::size_t i = 0; i < used_names.size(); ++i)
    if (material_of_name[i] < 0 && name_has_faces[i])
      result.warnings.push_back(
          at(path, used_names[i].second) + ": material '" + used_names[i].first +
          "' is not defined in any material library; its faces get " +
          (name_faces_coloured[i] ? std::string("their vertex colours") : std::string(default_material_text)));

  for (object_builder& obj : objects)
    if (!std::get<polygon_mesh>(obj.out.geometry).faces.empty()) result.surfaces.push_back(std::move(obj.out));
  if (result.surfaces.empty()) {
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) throw load_error(path + ": empty file");
    std::string what = path + ": no faces ('f')";
    if (!positions.empty()) what += "; " + std::to_string(positions.size()) + " vertices";
    for (const char* k : {"p", "l"})
      if (ignored_count.count(k))
        what += std::string(", ") + std::to_string(ignored_count[k]) + (k[0] == 'p' ? " points ('p')" : " lines ('l')");
    throw load_error(what + ": nothing with an area to light");
  }
}

}  // namespace

obj_read_result read_obj(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures) {
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) throw load_error(path + ": cannot read file");
  obj_read_result result;
  try {
    read_obj_statements(path, text_of(*bytes, path), materials, textures, result);
    return result;
  } catch (load_error& e) {
    // Keep what was said before the failure: it often explains it.
    e.warnings.insert(e.warnings.begin(), result.warnings.begin(), result.warnings.end());
    throw;
  }
}

}  // namespace bounce
