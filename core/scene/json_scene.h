// Bounce's JSON scene format (docs/scene-format.md): a .json file read
// into a `scene`, and the typed, strict access to JSON values it is read
// with. Every error names the file and the value's path inside it
// ("materials.white.rho"); unknown keys are errors, so that a misspelt key
// never silently does nothing. Camera files (camera_file.h) hold this
// format's camera object and are read with the same tools.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/reader_support.h"
#include "scene/scene.h"

namespace bounce {

// Typed access to a JSON document; every error names the file and the
// value's path inside it (e.g. "materials.white.rho"). Throws load_error.
struct json_reader {
  using json = nlohmann::json;
  std::string file;

  // `where` and `what` may quote the file (keys, names): kept to one line.
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw load_error(file + ": " + one_line(where) + ": " + one_line(what, 300));
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
  // magnitude (every reader's limit): intensities, emissions, backgrounds
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

// Parses `text` (the contents of `path`). Throws load_error naming the line
// and column of a syntax error or of a number literal beyond a double.
nlohmann::json parse_json(const std::string& path, const std::string& text);

// Reads a camera object ({"eye", "target", "up", "fov", "size"}) into
// `cam`; keys left out keep `cam`'s values. A scene's camera needs eye and
// target; a camera file (`partial`) may give any of them. On failure `cam`
// may be partly written.
void read_camera(const json_reader& r, const nlohmann::json& j, camera& cam, bool partial = false);

// Reads the .json scene `path` into `s` (whose source the caller sets):
// textures, materials, surfaces (the OBJ files they name included),
// lights, background, sky and camera (fitted to the geometry when the file
// has none). The OBJ files' warnings are appended to `warnings` and their
// dropped faces added to `dropped_faces` as they are read, so that they
// survive a later failure. Throws load_error.
void read_json_scene(const std::string& path, scene& s, std::vector<std::string>& warnings, std::size_t& dropped_faces);

}  // namespace bounce
