// What the scene readers (JSON scenes, OBJ/MTL, glTF, camera files) share:
// the error they throw, the limits every file obeys, reading a file from
// disk or from the binary, resolving a file's relative references, decoding
// image textures and printing numbers in messages. The readers take these
// from here, not from each other, so each format stays in a file of its
// own (a JSON scene still calls the OBJ reader for the OBJ files it names).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace bounce {

// Thrown by the readers; the message already names file and line or object.
// `warnings` holds what the reader had to say before it failed, so that the
// caller can print them before the error.
struct load_error : std::runtime_error {
  using std::runtime_error::runtime_error;
  std::vector<std::string> warnings;
};

// Limits on what a scene, OBJ, MTL or glTF file may say (see
// docs/scene-format.md). Every number must be finite and at most this in
// magnitude: no real scene has coordinates, colours or exponents near it,
// and it keeps areas, powers (pi * Ke * area) and the fitted camera far
// from overflow.
inline constexpr double max_file_number = 1e9;
// Faces with more corners are refused: ear clipping costs O(n r) for r
// reflex corners, which at this size is already slow in the worst case.
inline constexpr std::size_t max_face_corners = 10'000;
// Reflectances of 1 or more (Kd 1 1 1, vertex colours of 1) become this,
// as Valve's VRAD does; rho + kr + kt over 1 is scaled down to it.
inline constexpr double max_reflectance = 0.99;
// Colour channels above this are not reflectances at all (0-255 colours?)
// and are refused.
inline constexpr double max_colour_channel = 2.0;

// Reads a file's bytes, from disk or, for paths starting with "embedded:",
// from the files compiled into the binary (base/embedded.h). Nothing when
// the file is missing or unreadable.
std::optional<std::string> read_file(const std::string& path);

// Every file read on this thread while a log is alive: by read_file, and
// by the glTF and assimp readers' own reads (note_input_file). A command
// refuses outputs that would overwrite one of them (the scene, its MTL,
// textures, buffers).
class input_log {
 public:
  input_log();
  ~input_log();
  input_log(const input_log&) = delete;
  input_log& operator=(const input_log&) = delete;
  std::vector<std::string> files;

 private:
  input_log* outer_;
};
void note_input_file(const std::string& path);

// `relative` as named inside `base_file`: relative to the folder holding
// it (an "embedded:" folder too), or as given when absolute.
std::string resolve(const std::string& base_file, const std::string& relative);

// Reads an image texture (PNG, JPEG, ... via stb_image) into linear RGB.
// Throws load_error naming `where` (the file and line that asked for it).
texture read_image_texture(const std::string& path, const std::string& name, const std::string& where);

// The same for an image already in memory (one inside a glTF file); `what`
// names it in the message ("image 2").
texture decode_image_texture(std::string_view bytes, const std::string& name, const std::string& where,
                             const std::string& what);

// Text from a file as a message may quote it (a key, a name): on one line,
// control characters shown as '?', and at most `longest` bytes (the middle
// of a longer one left out).
std::string one_line(std::string text, std::size_t longest = 120);

// A JSON parser's reason for a message: nlohmann quotes what it "last
// read", which for a long string is the input at length, bytes of any
// kind included; kept to its last 40 characters, on one line, with bytes
// that are not printable ASCII shown as '?'.
std::string json_parse_reason(std::string reason);

// Numbers in the model readers' messages: %g, and a grey colour as one number.
std::string format_value(double v);
std::string format_value(const rgb& c);

}  // namespace bounce
