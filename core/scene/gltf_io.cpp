#include "scene/gltf_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string_view>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
// Debian's libtinygltf.so holds the implementation (TINYGLTF_IMPLEMENTATION
// is not defined here); the header only declares it.
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "scene/draco_mesh.h"
#include "scene/reader_support.h"
#include "scene/texture.h"

namespace bounce {
namespace {

// Past these a file is absurd for a radiosity scene (the OBJ reader's
// vertex limit) and would only exhaust memory.
constexpr std::size_t max_accessor_elements = 20'000'000;
// Deeper node trees are a cycle-like mistake (and recursion has limits).
constexpr int max_node_depth = 1000;

std::string indexed(const char* list, std::size_t i) {
  return std::string(list) + "[" + std::to_string(i) + "]";
}

// tinygltf's messages, one per line.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

// Keeps an image's encoded bytes instead of decoding it: only base colour
// images are decoded, later (a broken normal map then cannot fail the
// load). Images inside buffer views are copied later too, once their byte
// range is checked (tinygltf passes them unchecked).
// tinygltf's reads of buffers and images beside the file, through
// read_file: regular files only (a FIFO would block for ever), and noted
// as inputs.
bool read_whole_regular_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  const std::optional<std::string> bytes = read_file(path);
  if (!bytes) {
    std::error_code ec;
    if (err)
      *err += std::filesystem::exists(path, ec) ? "'" + path + "' is not a regular file\n"
                                                : "File not found : " + path + "\n";
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}

// tinygltf's own test opens the file, which blocks on a FIFO.
bool file_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf quotes a buffer's URI in its messages; an embedded one is the
// whole buffer in base64 (a megabyte). Each is shortened to its start and
// its length.
std::string without_data_uris(std::string line) {
  static const std::string base64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/=";
  for (std::size_t at = line.find("data:"); at != std::string::npos; at = line.find("data:", at + 1)) {
    const std::size_t comma = line.find(',', at);
    if (comma == std::string::npos) break;
    std::size_t end = line.find_first_not_of(base64, comma + 1);
    if (end == std::string::npos) end = line.size();
    if (end - comma <= 64) continue;
    line.replace(comma + 1, end - comma - 1, "... (" + std::to_string(end - comma - 1) + " characters)");
  }
  return line;
}

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + at, 4);  // glTF binaries are little-endian, as is every host Bounce runs on
  return v;
}

// The binary container's header and chunk lengths against the file's size
// (tinygltf's own check lets a BIN chunk run 8 bytes past the end).
void check_glb(const std::string& bytes, const std::string& path) {
  const std::size_t size = bytes.size();
  if (size < 20)
    throw load_error(path + ": truncated glTF binary: " + std::to_string(size) +
                     " bytes, less than the 20-byte header and JSON chunk header");
  if (const std::uint32_t version = u32_at(bytes, 4); version != 2)
    throw load_error(path + ": glTF binary version " + std::to_string(version) + "; Bounce reads version 2");
  const std::uint64_t length = u32_at(bytes, 8);
  if (length > size)
    throw load_error(path + ": truncated glTF binary: its header says " + std::to_string(length) +
                     " bytes, the file has " + std::to_string(size));
  const std::uint64_t json_length = u32_at(bytes, 12);
  if (u32_at(bytes, 16) != 0x4E4F534Au) throw load_error(path + ": glTF binary whose first chunk is not JSON");
  if (20 + json_length > length)
    throw load_error(path + ": truncated glTF binary: the JSON chunk (" + std::to_string(json_length) +
                     " bytes) runs past the end");
  const std::uint64_t bin = 20 + json_length;
  if (bin < length) {
    if (bin + 8 > length) throw load_error(path + ": truncated glTF binary: the BIN chunk header is cut off");
    const std::uint64_t bin_length = u32_at(bytes, bin);
    if (bin + 8 + bin_length > length)
      throw load_error(path + ": truncated glTF binary: the BIN chunk (" + std::to_string(bin_length) +
                       " bytes) runs past the end");
  }
}

// tinygltf (Debian's is built without Draco) refuses the accessors of a
// Draco-compressed primitive, which have no bufferView. Each is given the
// compressed stream's bufferView, which is never read through them: the
// reader decodes the stream instead. Text that is not JSON is left as it
// is, for tinygltf to report.
std::string place_draco_accessors(const std::string& text) {
  nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array() ||
      !doc.contains("accessors") || !doc["accessors"].is_array())
    return text;
  nlohmann::json& accessors = doc["accessors"];
  bool changed = false;
  auto place = [&](const nlohmann::json& accessor, const nlohmann::json& view) {
    if (!accessor.is_number_unsigned() || accessor.get<std::size_t>() >= accessors.size()) return;
    nlohmann::json& a = accessors[accessor.get<std::size_t>()];
    if (a.is_object() && !a.contains("bufferView")) {
      a["bufferView"] = view;
      changed = true;
    }
  };
  for (const nlohmann::json& mesh : doc["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (const nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
      const auto draco = prim["extensions"].find("KHR_draco_mesh_compression");
      if (draco == prim["extensions"].end() || !draco->is_object() || !draco->contains("bufferView")) continue;
      const nlohmann::json& view = (*draco)["bufferView"];
      if (prim.contains("indices")) place(prim["indices"], view);
      if (prim.contains("attributes") && prim["attributes"].is_object())
        for (const auto& [name, accessor] : prim["attributes"].items()) place(accessor, view);
    }
  }
  return changed ? doc.dump() : text;
}

// The same in a glTF binary: its JSON chunk replaced.
std::string place_draco_accessors_in_glb(const std::string& bytes) {
  const std::uint32_t json_length = u32_at(bytes, 12);
  std::string text = place_draco_accessors(bytes.substr(20, json_length));
  while (text.size() % 4) text += ' ';
  const std::string rest = bytes.substr(20 + std::size_t(json_length));
  auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  return bytes.substr(0, 8) + u32(std::uint32_t(20 + text.size() + rest.size())) + u32(std::uint32_t(text.size())) +
         "JSON" + text + rest;
}

// One primitive as triangles, in the mesh's own coordinates.
struct primitive_data {
  std::vector<vec3> positions;
  std::vector<vec3> normals;  // empty or one per position
  std::vector<vec2> uvs;      // empty or one per position (Bounce's v: 1 at the image's top)
  std::vector<std::array<int, 3>> triangles;
  int material = 0;  // index into the scene's materials
};

struct gltf_reader {
  const std::string& path;
  const tinygltf::Model& m;
  std::vector<material>& materials;
  std::vector<texture>& textures;
  gltf_read_result& result;

  gltf_reader(const std::string& path, const tinygltf::Model& model, std::vector<material>& materials,
              std::vector<texture>& textures, gltf_read_result& result)
      : path(path), m(model), materials(materials), textures(textures), result(result) {}

  std::map<std::pair<int, bool>, int> material_of;  // (glTF material, with texture) -> scene material
  std::map<int, int> texture_of;                    // glTF image -> scene texture
  std::map<int, std::vector<primitive_data>> meshes;
  std::set<std::string> said;  // kinds of warning already given
  std::set<int> clamped;       // glTF materials whose base colour was clamped
  std::string first_clamped;
  std::size_t skipped_primitives = 0;

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw load_error(path + ": " + where + ": " + what);
  }

  void warn_once(const std::string& kind, const std::string& text) {
    if (said.insert(kind).second) result.warnings.push_back(path + ": " + text);
  }

  // ---- accessors ------------------------------------------------------

  // The bytes [offset, offset + length) of buffer view `view`, checked.
  const unsigned char* view_bytes(int view, std::uint64_t offset, std::uint64_t length,
                                  const std::string& where) const {
    if (view < 0 || view >= int(m.bufferViews.size()))
      fail(where, "buffer view " + std::to_string(view) + " does not exist (the file has " +
                      std::to_string(m.bufferViews.size()) + ")");
    const tinygltf::BufferView& bv = m.bufferViews[view];
    const std::string at = where + ": " + indexed("bufferViews", view);
    if (bv.buffer < 0 || bv.buffer >= int(m.buffers.size()))
      fail(at, "buffer " + std::to_string(bv.buffer) + " does not exist (the file has " +
                   std::to_string(m.buffers.size()) + ")");
    const std::uint64_t buffer_size = m.buffers[bv.buffer].data.size();
    if (bv.byteLength > buffer_size || bv.byteOffset > buffer_size - bv.byteLength)
      fail(at, "bytes " + std::to_string(bv.byteOffset) + " to " + std::to_string(bv.byteOffset + bv.byteLength) +
                   " are beyond the end of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(buffer_size) +
                   " bytes)");
    if (length > bv.byteLength || offset > bv.byteLength - length)
      fail(where, "reads bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
                      " of buffer view " + std::to_string(view) + ", which has " + std::to_string(bv.byteLength));
    return m.buffers[bv.buffer].data.data() + bv.byteOffset + offset;
  }

  static double component(const unsigned char* p, int type, bool normalized) {
    auto get = [p]<typename T>(T) {
      T v;
      std::memcpy(&v, p, sizeof v);
      return v;
    };
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return normalized ? std::max(get(std::int8_t()) / 127.0, -1.0) : get(std::int8_t());
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? get(std::uint8_t()) / 255.0 : get(std::uint8_t());
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return normalized ? std::max(get(std::int16_t()) / 32767.0, -1.0) : get(std::int16_t());
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return normalized ? get(std::uint16_t()) / 65535.0 : get(std::uint16_t());
      case TINYGLTF_COMPONENT_TYPE_INT:
        return get(std::int32_t());
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return normalized ? get(std::uint32_t()) / 4294967295.0 : get(std::uint32_t());
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return get(float());
      default:
        return get(double());
    }
  }

  // Accessor `index` as count x components numbers, sparse values applied.
  // `where` names who asks ("meshes[0].primitives[1].attributes.POSITION").
  std::vector<double> read_accessor(int index, int type, const std::string& where) const {
    if (index < 0 || index >= int(m.accessors.size()))
      fail(where, "accessor " + std::to_string(index) + " does not exist (the file has " +
                      std::to_string(m.accessors.size()) + ")");
    const tinygltf::Accessor& a = m.accessors[index];
    const std::string at = where + " (accessor " + std::to_string(index) + ")";
    static const std::map<int, const char*> type_names = {
        {TINYGLTF_TYPE_SCALAR, "SCALAR"}, {TINYGLTF_TYPE_VEC2, "VEC2"}, {TINYGLTF_TYPE_VEC3, "VEC3"},
        {TINYGLTF_TYPE_VEC4, "VEC4"},     {TINYGLTF_TYPE_MAT2, "MAT2"}, {TINYGLTF_TYPE_MAT3, "MAT3"},
        {TINYGLTF_TYPE_MAT4, "MAT4"}};
    if (a.type != type) {
      auto it = type_names.find(a.type);
      fail(at, std::string("type is ") + (it != type_names.end() ? it->second : "unknown") + ", expected " +
                   type_names.at(type));
    }
    const int component_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    if (component_size <= 0) fail(at, "unknown component type " + std::to_string(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    const std::uint64_t element = std::uint64_t(component_size) * components;
    if (a.count > max_accessor_elements)
      fail(at, std::to_string(a.count) + " elements; Bounce takes at most " + std::to_string(max_accessor_elements));
    // Byte ranges first, so that a bad count cannot allocate much.
    const unsigned char* base = nullptr;
    std::uint64_t stride = element;
    if (a.bufferView >= 0 && a.count > 0) {
      if (a.bufferView < int(m.bufferViews.size()) && m.bufferViews[a.bufferView].byteStride)
        stride = m.bufferViews[a.bufferView].byteStride;
      if (stride < element || stride > 252)
        fail(at, "byte stride " + std::to_string(stride) + " does not fit elements of " + std::to_string(element) +
                     " bytes (it must be from the element size to 252)");
      if (a.byteOffset > std::numeric_limits<std::uint32_t>::max())
        fail(at, "byte offset " + std::to_string(a.byteOffset) + " is out of range");
      base = view_bytes(a.bufferView, a.byteOffset, stride * (a.count - 1) + element, at);
    }
    std::vector<double> out(a.count * components, 0.0);  // no buffer view: zeros, as the specification says
    if (base)
      for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < components; ++c)
          out[i * components + c] = component(base + i * stride + c * component_size, a.componentType, a.normalized);
    if (a.sparse.isSparse) {
      const auto& sp = a.sparse;
      const std::string sat = at + ".sparse";
      if (sp.count < 1 || std::size_t(sp.count) > a.count)
        fail(sat, "count " + std::to_string(sp.count) + " must be from 1 to the accessor's " + std::to_string(a.count));
      const int index_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(sp.indices.componentType));
      if (sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(sat + ".indices", "component type must be an unsigned integer");
      if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) fail(sat, "negative byte offset");
      const unsigned char* indices = view_bytes(sp.indices.bufferView, std::uint64_t(sp.indices.byteOffset),
                                                std::uint64_t(index_size) * sp.count, sat + ".indices");
      const unsigned char* values =
          view_bytes(sp.values.bufferView, std::uint64_t(sp.values.byteOffset), element * sp.count, sat + ".values");
      for (int k = 0; k < sp.count; ++k) {
        const double target = component(indices + std::size_t(k) * index_size, sp.indices.componentType, false);
        if (target >= double(a.count))
          fail(sat + ".indices",
               "index " + format_value(target) + " is out of range (" + std::to_string(a.count) + " elements)");
        for (int c = 0; c < components; ++c)
          out[std::size_t(target) * components + c] =
              component(values + (std::size_t(k) * components + c) * component_size, a.componentType, a.normalized);
      }
    }
    return out;
  }

  // A vertex attribute: `count` (or any, if -1) vectors of N numbers, all finite.
  template <int N>
  std::vector<glm::vec<N, double>> read_vectors(int accessor, int count, const std::string& where) const {
    const int type = N == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
    const std::vector<double> flat = read_accessor(accessor, type, where);
    const std::string at = where + " (accessor " + std::to_string(accessor) + ")";
    const std::size_t n = flat.size() / N;
    if (count >= 0 && n != std::size_t(count))
      fail(at, "has " + std::to_string(n) + " elements, POSITION has " + std::to_string(count));
    std::vector<glm::vec<N, double>> out(n);
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < N; ++c) {
        const double v = flat[i * N + c];
        if (!std::isfinite(v))
          fail(at, "element " + std::to_string(i) + " is not a finite number (" + format_value(v) + ")");
        if (std::abs(v) > max_file_number)
          fail(at, "element " + std::to_string(i) + " is out of range (" + format_value(v) + "; the limit is " +
                       format_value(max_file_number) + " in magnitude)");
        out[i][c] = v;
      }
    return out;
  }

  // ---- materials and textures -----------------------------------------

  int decode_image(int image, const std::string& where) {
    if (auto it = texture_of.find(image); it != texture_of.end()) return it->second;
    if (image < 0 || image >= int(m.images.size()))
      fail(where,
           "image " + std::to_string(image) + " does not exist (the file has " + std::to_string(m.images.size()) + ")");
    const tinygltf::Image& img = m.images[image];
    const std::string at = indexed("images", image);
    std::string_view bytes;
    if (img.bufferView >= 0) {
      const std::uint64_t length =
          img.bufferView < int(m.bufferViews.size()) ? m.bufferViews[img.bufferView].byteLength : 0;
      bytes = std::string_view(reinterpret_cast<const char*>(view_bytes(img.bufferView, 0, length, at)), length);
    } else {
      bytes = std::string_view(reinterpret_cast<const char*>(img.image.data()), img.image.size());
    }
    const bool external = img.bufferView < 0 && !img.uri.empty() && img.uri.rfind("data:", 0) != 0;
    const std::string file =
        external ? (std::filesystem::path(path).parent_path() / img.uri).lexically_normal().string() : "";
    if (bytes.empty()) fail(at, external ? "cannot read texture '" + file + "'" : "image has no data");
    const std::string name = external ? img.uri : path + "#" + at;
    textures.push_back(decode_image_texture(bytes, name, path + ": " + at,
                                            external ? "texture '" + file + "'" : "image " + std::to_string(image)));
    texture_of[image] = int(textures.size()) - 1;
    return texture_of[image];
  }

  // The scene texture of a base colour texture, or -1 (with a warning) when
  // its image is in a format only an extension defines.
  int base_colour_texture(int index, const std::string& where) {
    if (index >= int(m.textures.size()))
      fail(where, "texture " + std::to_string(index) + " does not exist (the file has " +
                      std::to_string(m.textures.size()) + ")");
    const tinygltf::Texture& t = m.textures[index];
    if (t.source < 0) {
      warn_once("source", indexed("textures", index) +
                              ": no PNG or JPEG source (an image format only an extension defines); base colour "
                              "textures without one are ignored");
      return -1;
    }
    if (t.sampler >= int(m.samplers.size()))
      fail(indexed("textures", index), "sampler " + std::to_string(t.sampler) + " does not exist");
    if (t.sampler >= 0) {
      const tinygltf::Sampler& s = m.samplers[t.sampler];
      if (s.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || s.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
        warn_once("wrap", indexed("samplers", t.sampler) +
                              ": clamped and mirrored texture wrapping is read as repeat (Bounce's image textures "
                              "repeat)");
    }
    return decode_image(t.source, indexed("textures", index) + ".source");
  }

  // The scene material for glTF material `index` (-1: glTF's default);
  // A number in a material extension (`fallback` when absent), in [lo, hi].
  double extension_number(const tinygltf::Value& extension, const char* key, double fallback, double lo, double hi,
                          const std::string& who) {
    if (!extension.Has(key)) return fallback;
    const tinygltf::Value& v = extension.Get(key);
    const double x = v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
    if (!(x >= lo && x <= hi))
      fail(who, std::string(key) + " must be a number from " + format_value(lo) + " to " + format_value(hi));
    return x;
  }

  // `textured` false drops its texture (for primitives without uvs).
  int scene_material(int index, bool textured) {
    if (auto it = material_of.find({index, textured}); it != material_of.end()) return it->second;
    material out;
    if (index < 0) {
      // As the OBJ reader does for faces without a material.
      out.name = "default";
      out.rho = rgb(0.5);
      warn_once("default material", "primitives without a material get the grey default material (rho 0.5)");
    } else {
      const tinygltf::Material& g = m.materials[index];
      const std::string where = indexed("materials", index);
      const std::string who = where + (g.name.empty() ? "" : " '" + g.name + "'");
      out.name = g.name.empty() ? where : g.name;
      const auto& pbr = g.pbrMetallicRoughness;
      if (pbr.baseColorFactor.size() != 4) fail(who, "baseColorFactor needs 4 numbers");
      rgb c(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
      if (!std::isfinite(c.r + c.g + c.b) || glm::any(glm::lessThan(c, rgb(0.0))) ||
          glm::any(glm::greaterThan(c, rgb(max_colour_channel))))
        fail(who, "baseColorFactor " + format_value(c) + " is not a reflectance (channels go from 0 to 1)");
      // Channels of 1 or more are clamped as the OBJ reader clamps Kd 1 (glTF's default base colour is 1).
      bool clamp = false;
      for (int i = 0; i < 3; ++i)
        if (c[i] >= 1.0) {
          c[i] = max_reflectance;
          clamp = true;
        }
      if (clamp && clamped.insert(index).second && first_clamped.empty()) first_clamped = who;
      out.rho = c;
      if (g.emissiveFactor.size() != 3) fail(who, "emissiveFactor needs 3 numbers");
      rgb ke(g.emissiveFactor[0], g.emissiveFactor[1], g.emissiveFactor[2]);
      if (!std::isfinite(ke.r + ke.g + ke.b) || glm::any(glm::lessThan(ke, rgb(0.0))))
        fail(who, "emissiveFactor " + format_value(ke) + " must be finite and not negative");
      if (auto it = g.extensions.find("KHR_materials_emissive_strength"); it != g.extensions.end()) {
        const tinygltf::Value& strength = it->second.Get("emissiveStrength");
        if (it->second.Has("emissiveStrength")) {
          if (!strength.IsNumber() || !(strength.GetNumberAsDouble() >= 0.0) ||
              !std::isfinite(strength.GetNumberAsDouble()))
            fail(who, "KHR_materials_emissive_strength.emissiveStrength must be a number >= 0");
          ke *= strength.GetNumberAsDouble();
        }
      }
      out.ke = ke;
      if (textured && pbr.baseColorTexture.index >= 0)
        out.texture = base_colour_texture(pbr.baseColorTexture.index, where + ".pbrMetallicRoughness.baseColorTexture");
      // Metallic-roughness: a smooth metal is a mirror tinted by its base
      // colour (kr = metallic x base, rho the rest); a rough one stays
      // diffuse, as Bounce has no glossy reflection.
      const double metallic = std::clamp(pbr.metallicFactor, 0.0, 1.0);
      const double roughness = std::clamp(pbr.roughnessFactor, 0.0, 1.0);
      if (metallic >= gltf_mirror_metallic && roughness <= gltf_mirror_roughness) {
        out.kr = metallic * out.rho;
        out.rho = (1.0 - metallic) * out.rho;
      } else if (metallic > 0.0) {
        warn_once("metallic", who +
                                  ": metallic and roughness ignored for rough metals (and in every other material): "
                                  "a metal is a mirror when metallicFactor >= 0.5 and roughnessFactor <= 0.25, "
                                  "otherwise diffuse, rho = baseColorFactor x baseColorTexture");
      }
      // KHR_materials_transmission (+ _ior, _volume): glass. Without a
      // volume the surface is thin-walled (glTF's default): light passes
      // straight through, with the interface's reflection at normal
      // incidence; with one, it is the boundary of a solid that refracts.
      if (auto it = g.extensions.find("KHR_materials_transmission"); it != g.extensions.end()) {
        const double transmission = extension_number(it->second, "transmissionFactor", 0.0, 0.0, 1.0, who);
        double ior = 1.5;
        if (auto i = g.extensions.find("KHR_materials_ior"); i != g.extensions.end())
          ior = extension_number(i->second, "ior", 1.5, 1.0, 10.0, who);
        double thickness = 0.0;
        if (auto v = g.extensions.find("KHR_materials_volume"); v != g.extensions.end())
          thickness = extension_number(v->second, "thicknessFactor", 0.0, 0.0, 1e9, who);
        if (transmission > 0.0) {
          const rgb base = out.rho;  // what metallic left of the base colour
          out.rho = (1.0 - transmission) * base;
          if (thickness > 0.0) {
            out.kt = transmission * base;
            out.ior = ior;
            out.fresnel = true;
          } else {
            const double r0 = (ior - 1.0) * (ior - 1.0) / ((ior + 1.0) * (ior + 1.0));
            out.kt = transmission * (1.0 - r0) * base;
            out.kr += transmission * r0 * base;
            out.ior = 1.0;
          }
          if (roughness > gltf_mirror_roughness)
            warn_once("rough transmission", who +
                                                ": roughness ignored for transmission (and in every other "
                                                "material): Bounce's glass is clear");
          if (it->second.Has("transmissionTexture"))
            warn_once("transmission texture", who + ": transmissionTexture ignored (and in every other material)");
        }
      }
      if (pbr.metallicRoughnessTexture.index >= 0)
        warn_once("metallic texture", who +
                                          ": metallicRoughnessTexture ignored (and in every other material): "
                                          "the factors alone decide mirror or diffuse");
      if (g.normalTexture.index >= 0) warn_once("normal", who + ": normal maps ignored (and in every other material)");
      if (g.occlusionTexture.index >= 0)
        warn_once("occlusion", who +
                                   ": occlusion maps ignored (and in every other material): radiosity computes "
                                   "the occlusion itself");
      // An emissive texture: the surface glows where the texture does, with
      // the power of its mean (a label is not a lamp).
      if (textured && g.emissiveTexture.index >= 0 && any_positive(out.ke)) {
        const int t = base_colour_texture(g.emissiveTexture.index, where + ".emissiveTexture");
        if (t >= 0) {
          out.ke *= texture_mean(textures[std::size_t(t)]);
          out.emission_texture = t;
        }
        const auto& base = g.pbrMetallicRoughness.baseColorTexture;
        if (base.index >= 0 && base.texCoord != g.emissiveTexture.texCoord)
          warn_once("emissive uv", who +
                                       ": the emissive texture is read with the base colour texture's "
                                       "TEXCOORD_" +
                                       std::to_string(base.texCoord) + " (and in every other material)");
      }
      if (g.alphaMode == "MASK") {
        // A cut-out: no surface where the base colour's alpha is below the cutoff.
        if (!(g.alphaCutoff >= 0.0 && g.alphaCutoff <= 1.0)) fail(who, "alphaCutoff must be from 0 to 1");
        const double alpha = pbr.baseColorFactor[3];
        if (!(alpha >= 0.0 && alpha <= 1.0)) fail(who, "baseColorFactor's alpha must be from 0 to 1");
        out.alpha = alpha;
        out.alpha_cutoff = g.alphaCutoff;
      } else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) {
        warn_once("alpha",
                  who + ": alphaMode " + g.alphaMode + " ignored (and in every other material): surfaces are opaque");
      }
      out.two_sided = g.doubleSided;
    }
    materials.push_back(out);
    material_of[{index, textured}] = int(materials.size()) - 1;
    return int(materials.size()) - 1;
  }

  // ---- meshes ---------------------------------------------------------

  // The Draco stream of a compressed primitive, decoded with the attributes
  // the primitive uses (POSITION, NORMAL, TEXCOORD_n).
  draco_mesh decode_draco(const tinygltf::Value& extension, const tinygltf::Primitive& prim, const std::string& at) {
    const std::string where = at + ".extensions.KHR_draco_mesh_compression";
    if (!extension.Has("bufferView") || !extension.Get("bufferView").IsNumber()) fail(where, "needs a 'bufferView'");
    const int view = extension.Get("bufferView").GetNumberAsInt();
    if (view < 0 || view >= int(m.bufferViews.size()))
      fail(where, "bufferView " + std::to_string(view) + " does not exist (the file has " +
                      std::to_string(m.bufferViews.size()) + ")");
    const std::uint64_t length = m.bufferViews[std::size_t(view)].byteLength;
    const auto* bytes = view_bytes(view, 0, length, where);
    std::map<int, int> wanted;
    const tinygltf::Value& ids = extension.Get("attributes");
    for (const auto& [name, accessor] : prim.attributes) {
      if (!ids.Has(name)) continue;
      if (!ids.Get(name).IsNumber()) fail(where, "attribute '" + name + "' needs a number");
      const int components = name == "POSITION" || name == "NORMAL" ? 3 : name.rfind("TEXCOORD_", 0) == 0 ? 2 : 0;
      const int id = ids.Get(name).GetNumberAsInt();
      if (components > 0 && wanted.count(id) && wanted[id] != components)
        fail(where,
             "attributes '" + name + "' and another of a different size name Draco attribute " + std::to_string(id));
      if (components > 0) wanted[id] = components;
    }
    if (!ids.Has("POSITION")) fail(where, "has no POSITION");
    draco_mesh out;
    if (std::string e = decode_draco_mesh(std::string_view(reinterpret_cast<const char*>(bytes), length), wanted, out);
        !e.empty())
      fail(where, e);
    for (const std::array<int, 3>& t : out.triangles)
      for (int v : t)
        if (v < 0 || std::size_t(v) >= out.points)
          fail(where, "a triangle names point " + std::to_string(v) + " of " + std::to_string(out.points));
    return out;
  }

  const std::vector<primitive_data>& mesh(int index, const std::string& where) {
    if (auto it = meshes.find(index); it != meshes.end()) return it->second;
    if (index < 0 || index >= int(m.meshes.size()))
      fail(where,
           "mesh " + std::to_string(index) + " does not exist (the file has " + std::to_string(m.meshes.size()) + ")");
    std::vector<primitive_data> out;
    const tinygltf::Mesh& gm = m.meshes[index];
    for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = gm.primitives[p];
      const std::string at = indexed("meshes", index) + "." + indexed("primitives", p);
      if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
        ++skipped_primitives;
        warn_once("mode", at + ": points and lines have no area; primitives of them are skipped");
        continue;
      }
      if (prim.mode < TINYGLTF_MODE_POINTS || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        fail(at, "unknown mode " + std::to_string(prim.mode));
      if (!prim.targets.empty())
        warn_once("morph", at + ": morph targets ignored (and on every other primitive): meshes are read in "
                                "their base shape");
      auto attribute = [&](const std::string& name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
      };
      const int position = attribute("POSITION");
      if (position < 0) {
        ++skipped_primitives;
        warn_once("no position", at + ": a primitive without POSITION is skipped (as the specification says)");
        continue;
      }
      primitive_data d;
      // KHR_draco_mesh_compression: the attributes and indices come from
      // the compressed stream, not from the accessors.
      const auto draco = prim.extensions.find("KHR_draco_mesh_compression");
      draco_mesh decoded;
      auto draco_id = [&](const std::string& name) {
        const tinygltf::Value& ids = draco->second.Get("attributes");
        return ids.Has(name) && ids.Get(name).IsNumber() ? ids.Get(name).GetNumberAsInt() : -1;
      };
      if (draco != prim.extensions.end()) decoded = decode_draco(draco->second, prim, at);
      auto vectors = [&]<int n>(const std::string& name, int accessor, int count) {
        if (draco == prim.extensions.end()) return read_vectors<n>(accessor, count, at + ".attributes." + name);
        std::vector<glm::vec<n, double>> out(decoded.points);
        const std::vector<double>& values = decoded.attributes.at(draco_id(name));
        if (values.size() != out.size() * std::size_t(n))
          fail(at + ".extensions.KHR_draco_mesh_compression",
               name + " shares its Draco attribute with an attribute of another size");
        for (std::size_t i = 0; i < out.size(); ++i)
          for (int c = 0; c < n; ++c) {
            const double x = values[i * n + std::size_t(c)];
            if (!std::isfinite(x) || std::abs(x) > max_file_number)
              fail(at + ".extensions.KHR_draco_mesh_compression",
                   name + " of point " + std::to_string(i) + " is out of range (" + format_value(x) + ")");
            out[i][c] = x;
          }
        return out;
      };
      d.positions = vectors.template operator()<3>("POSITION", position, -1);
      const int count = int(d.positions.size());
      if (const int normal = attribute("NORMAL");
          normal >= 0 && (draco == prim.extensions.end() || draco_id("NORMAL") >= 0)) {
        d.normals = vectors.template operator()<3>("NORMAL", normal, count);
        for (vec3& n : d.normals) n = glm::length(n) > 0.0 ? glm::normalize(n) : vec3(0.0);
      }
      if (prim.material >= int(m.materials.size()))
        fail(at, "material " + std::to_string(prim.material) + " does not exist (the file has " +
                     std::to_string(m.materials.size()) + ")");
      bool textured = false;
      int texcoord = 0;
      if (prim.material >= 0) {
        // The base colour texture's set, else the emissive texture's.
        const tinygltf::Material& mat = m.materials[prim.material];
        const auto& base = mat.pbrMetallicRoughness.baseColorTexture;
        textured = base.index >= 0 || mat.emissiveTexture.index >= 0;
        texcoord = base.index >= 0 ? base.texCoord : mat.emissiveTexture.texCoord;
      }
      if (textured) {
        const std::string set = "TEXCOORD_" + std::to_string(texcoord);
        if (const int uv = attribute(set); uv >= 0 && (draco == prim.extensions.end() || draco_id(set) >= 0)) {
          d.uvs = vectors.template operator()<2>(set, uv, count);
          for (vec2& t : d.uvs) t.y = 1.0 - t.y;  // glTF's v runs down the image, Bounce's up
        } else {
          textured = false;
          warn_once("no uv", at + ": its material's textures need " + set + ", which it lacks; they are ignored there");
        }
      }
      d.material = scene_material(prim.material, textured);

      std::vector<int> indices;
      if (draco != prim.extensions.end()) {
        for (const std::array<int, 3>& t : decoded.triangles) indices.insert(indices.end(), t.begin(), t.end());
      } else if (prim.indices >= 0) {
        const std::string iat = at + ".indices";
        const std::vector<double> flat = read_accessor(prim.indices, TINYGLTF_TYPE_SCALAR, iat);
        const int type = m.accessors[prim.indices].componentType;
        if ((type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ||
            m.accessors[prim.indices].normalized)
          fail(iat + " (accessor " + std::to_string(prim.indices) + ")",
               "component type must be an unsigned byte, short or int, not normalized");
        indices.reserve(flat.size());
        for (std::size_t i = 0; i < flat.size(); ++i) {
          if (flat[i] >= double(count))
            fail(iat + " (accessor " + std::to_string(prim.indices) + ")",
                 "element " + std::to_string(i) + " is vertex " + format_value(flat[i]) + ", out of range (" +
                     std::to_string(count) + " vertices)");
          indices.push_back(int(flat[i]));
        }
      } else {
        for (int i = 0; i < count; ++i) indices.push_back(i);
      }
      const std::size_t n = indices.size();
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0)
          warn_once("leftover", at + ": " + std::to_string(n) +
                                    " vertices is not a whole number of triangles; the last " + std::to_string(n % 3) +
                                    " are ignored");
        for (std::size_t i = 0; i + 2 < n; i += 3) d.triangles.push_back({indices[i], indices[i + 1], indices[i + 2]});
      } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < n; ++i)
          d.triangles.push_back(i % 2 ? std::array<int, 3>{indices[i + 1], indices[i], indices[i + 2]}
                                      : std::array<int, 3>{indices[i], indices[i + 1], indices[i + 2]});
      } else {  // fan
        for (std::size_t i = 1; i + 1 < n; ++i) d.triangles.push_back({indices[0], indices[i], indices[i + 1]});
      }
      out.push_back(std::move(d));
    }
    return meshes[index] = std::move(out);
  }

  // ---- nodes ----------------------------------------------------------

  glm::dmat4 local_transform(const tinygltf::Node& n, const std::string& where) const {
    auto finite = [&](const std::vector<double>& v, const char* what) {
      for (double x : v)
        if (!std::isfinite(x) || std::abs(x) > max_file_number)
          fail(where, std::string(what) + " holds " + format_value(x) + " (numbers are limited to " +
                          format_value(max_file_number) + " in magnitude)");
    };
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) fail(where, "matrix needs 16 numbers");
      finite(n.matrix, "matrix");
      return glm::make_mat4(n.matrix.data());  // both column-major
    }
    glm::dmat4 t(1.0);
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) fail(where, "translation needs 3 numbers");
      finite(n.translation, "translation");
      t = glm::translate(t, vec3(n.translation[0], n.translation[1], n.translation[2]));
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) fail(where, "rotation needs 4 numbers (a quaternion x, y, z, w)");
      finite(n.rotation, "rotation");
      glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      if (glm::length(q) == 0.0) fail(where, "rotation is the zero quaternion");
      t = t * glm::mat4_cast(glm::normalize(q));
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) fail(where, "scale needs 3 numbers");
      finite(n.scale, "scale");
      t = glm::scale(t, vec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return t;
  }

  void add_instance(int mesh_index, const glm::dmat4& world, const std::string& name, const std::string& where) {
    const std::vector<primitive_data>& prims = mesh(mesh_index, where + ".mesh");
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    const bool mirrored = det < 0.0;
    const bool keep_normals = std::isfinite(det) && det != 0.0;
    const glm::dmat3 normal_matrix = keep_normals ? glm::inverseTranspose(linear) : glm::dmat3(1.0);
    surface surf;
    surf.name = name;
    surf.source = path;
    polygon_mesh pm;
    for (const primitive_data& d : prims) {
      const int base = int(pm.positions.size());
      const int normal_base = int(pm.normals.size());
      const int uv_base = int(pm.uvs.size());
      for (const vec3& p : d.positions) {
        const vec3 q = vec3(world * glm::dvec4(p, 1.0));
        if (!std::isfinite(q.x + q.y + q.z) || glm::any(glm::greaterThan(glm::abs(q), vec3(max_file_number))))
          fail(where, "a vertex of mesh " + std::to_string(mesh_index) + " lands at (" + format_value(q.x) + ", " +
                          format_value(q.y) + ", " + format_value(q.z) + ") after the node transforms, beyond " +
                          format_value(max_file_number));
        pm.positions.push_back(q);
      }
      const bool normals = keep_normals && !d.normals.empty();
      if (normals)
        for (const vec3& n : d.normals) {
          const vec3 t = normal_matrix * n;
          pm.normals.push_back(glm::length(t) > 0.0 ? glm::normalize(t) : vec3(0.0));
        }
      pm.uvs.insert(pm.uvs.end(), d.uvs.begin(), d.uvs.end());
      for (std::array<int, 3> tri : d.triangles) {
        // A mirroring transform turns anticlockwise corners clockwise:
        // reversing them keeps the faces facing out.
        if (mirrored) std::swap(tri[1], tri[2]);
        polygon_face f;
        f.material = d.material;
        for (int i : tri) {
          f.position.push_back(base + i);
          if (normals) f.normal.push_back(normal_base + i);
          if (!d.uvs.empty()) f.uv.push_back(uv_base + i);
        }
        pm.faces.push_back(std::move(f));
      }
    }
    if (pm.faces.empty()) return;
    surf.geometry = std::move(pm);
    result.surfaces.push_back(std::move(surf));
  }

  // KHR_lights_punctual: a node's light, placed by the node's transform
  // (a light shines down its node's -Z). The extension's units are
  // photometric (candela for point and spot lights, lux for a sun) and the
  // numbers are kept as they are: emission is read on the same scale
  // (docs/scene-format.md).
  void add_light(int index, const glm::dmat4& world, const std::string& where) {
    if (index < 0 || index >= int(m.lights.size()))
      fail(where + ".light",
           "light " + std::to_string(index) + " does not exist (the file has " + std::to_string(m.lights.size()) + ")");
    const tinygltf::Light& l = m.lights[std::size_t(index)];
    const std::string who = "extensions.KHR_lights_punctual." + indexed("lights", std::size_t(index));
    rgb colour(1.0);
    if (!l.color.empty()) {
      if (l.color.size() != 3) fail(who, "color must have 3 numbers");
      colour = rgb(l.color[0], l.color[1], l.color[2]);
    }
    if (!glm::all(glm::greaterThanEqual(colour, rgb(0.0))) || !std::isfinite(channel_sum(colour)) ||
        !(l.intensity >= 0.0) || !std::isfinite(l.intensity))
      fail(who, "color and intensity must be finite and >= 0");
    punctual_light light;
    light.intensity = colour * l.intensity;
    light.position = vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const vec3 axis = vec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
    if (l.type == "spot" || l.type == "directional") {
      if (!(glm::length(axis) > 0.0) || !std::isfinite(glm::length(axis)))
        fail(where, "the node's transform gives its light no direction");
      light.direction = glm::normalize(axis);
    }
    if (l.type == "spot") {
      light.type = light_type::spot;
      light.inner_cone = l.spot.innerConeAngle;
      light.outer_cone = l.spot.outerConeAngle;
      if (!(light.inner_cone >= 0.0 && light.inner_cone < light.outer_cone &&
            light.outer_cone <= 0.5 * std::numbers::pi))
        fail(who, "spot cone angles need 0 <= innerConeAngle < outerConeAngle <= pi/2");
    } else if (l.type == "directional") {
      light.type = light_type::sun;
    } else if (l.type != "point") {
      fail(who, "type '" + l.type + "' is not point, spot or directional");
    }
    if (l.range > 0.0)
      warn_once("light range", who +
                                   ": range ignored (and on every other light): light falls off as 1/d^2 "
                                   "to any distance, as the extension allows");
    result.lights.push_back(light);
  }

  void visit(int node, const glm::dmat4& parent, std::vector<int>& path_to, const std::string& where) {
    if (node < 0 || node >= int(m.nodes.size()))
      fail(where,
           "node " + std::to_string(node) + " does not exist (the file has " + std::to_string(m.nodes.size()) + ")");
    const std::string at = indexed("nodes", node);
    if (std::find(path_to.begin(), path_to.end(), node) != path_to.end())
      fail(at, "is its own ancestor (the node hierarchy has a cycle)");
    if (int(path_to.size()) >= max_node_depth)
      fail(at, "the node hierarchy is deeper than " + std::to_string(max_node_depth));
    const tinygltf::Node& n = m.nodes[node];
    const glm::dmat4 world = parent * local_transform(n, at);
    if (n.skin >= 0)
      warn_once("skin", at + ": skins ignored (and on every other node): skinned meshes are read in their bind "
                             "pose, placed by their node");
    if (n.mesh >= 0) {
      std::string name = n.name;
      if (name.empty() && n.mesh < int(m.meshes.size())) name = m.meshes[n.mesh].name;
      if (name.empty()) name = at;
      add_instance(n.mesh, world, name, at);
    }
    if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
      const std::string where = at + ".extensions.KHR_lights_punctual";
      if (!it->second.Has("light") || !it->second.Get("light").IsNumber()) fail(where, "needs a 'light' index");
      add_light(it->second.Get("light").GetNumberAsInt(), world, where);
    }
    path_to.push_back(node);
    for (std::size_t c = 0; c < n.children.size(); ++c)
      visit(n.children[c], world, path_to, at + "." + indexed("children", c));
    path_to.pop_back();
  }

  void read() {
    // tinygltf reads a 1.0 file's JSON without complaint and finds nothing
    // in it; the version says why.
    if (!m.asset.version.empty() && m.asset.version[0] != '2')
      throw load_error(path + ": glTF version " + m.asset.version + "; Bounce reads version 2");
    static const std::set<std::string> supported = {
        "KHR_materials_emissive_strength", "KHR_mesh_quantization", "KHR_lights_punctual", "KHR_draco_mesh_compression",
        "KHR_materials_transmission",      "KHR_materials_ior",     "KHR_materials_volume"};
    // Extensions whose geometry Bounce cannot read: ignoring them would
    // give garbage, not an approximation.
    static const std::set<std::string> unreadable = {"EXT_meshopt_compression"};
    for (const std::string& e : m.extensionsRequired)
      if (unreadable.count(e)) fail("extensionsRequired", "'" + e + "' (compressed geometry) is not supported");
    for (const std::string& e : m.extensionsUsed) {
      if (supported.count(e)) continue;
      warn_once(e, "extension '" + e + "' is not supported; ignored");
    }
    if (!m.cameras.empty()) warn_once("camera", "cameras ignored: the camera is fitted to the geometry");
    if (!m.animations.empty()) warn_once("animation", "animations ignored: the scene is read at rest");

    std::vector<int> path_to;
    if (!m.scenes.empty()) {
      const int scene = m.defaultScene >= 0 ? m.defaultScene : 0;
      if (scene >= int(m.scenes.size()))
        fail("scene", "scene " + std::to_string(scene) + " does not exist (the file has " +
                          std::to_string(m.scenes.size()) + ")");
      const std::vector<int>& roots = m.scenes[scene].nodes;
      for (std::size_t i = 0; i < roots.size(); ++i)
        visit(roots[i], glm::dmat4(1.0), path_to, indexed("scenes", scene) + "." + indexed("nodes", i));
    } else if (!m.nodes.empty()) {
      // No scene: every node that is nobody's child is a root.
      std::vector<bool> child(m.nodes.size(), false);
      for (const tinygltf::Node& n : m.nodes)
        for (int c : n.children)
          if (c >= 0 && c < int(child.size())) child[c] = true;
      for (std::size_t i = 0; i < m.nodes.size(); ++i)
        if (!child[i]) visit(int(i), glm::dmat4(1.0), path_to, indexed("nodes", i));
    } else {
      for (std::size_t i = 0; i < m.meshes.size(); ++i)
        add_instance(int(i), glm::dmat4(1.0), m.meshes[i].name.empty() ? indexed("meshes", i) : m.meshes[i].name,
                     indexed("meshes", i));
    }
    if (!clamped.empty())
      result.warnings.push_back(path + ": " + first_clamped +
                                (clamped.size() > 1 ? " and " + std::to_string(clamped.size() - 1) + " more" : "") +
                                ": baseColorFactor channels of 1 or more clamped to " + format_value(max_reflectance) +
                                " (a reflectance of 1 or more would create energy)");
    if (result.surfaces.empty()) {
      std::string what = "no triangles in the scene: nothing with an area to light";
      if (skipped_primitives)
        what += " (" + std::to_string(skipped_primitives) + " primitive" + (skipped_primitives > 1 ? "s" : "") +
                " of points or lines skipped)";
      throw load_error(path + ": " + what);
    }
  }
};

}  // namespace

gltf_read_result read_gltf(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures) {
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) throw load_error(path + ": cannot read file");
  if (bytes->size() > std::numeric_limits<unsigned int>::max()) throw load_error(path + ": larger than 4 GB");
  gltf_read_result result;
  try {
    // The content decides, not the extension: .gltf files that are binary exist.
    const bool binary = bytes->size() >= 4 && bytes->compare(0, 4, "glTF") == 0;
    if (binary) check_glb(*bytes, path);
    const std::size_t first = bytes->find_first_not_of(" \t\r\n\xEF\xBB\xBF");
    if (!binary && (first == std::string::npos || (*bytes)[first] != '{'))
      throw load_error(path + (bytes->empty() ? ": empty file"
                                              : ": neither a glTF binary (it does not start with 'glTF') nor "
                                                "glTF JSON (it does not start with '{')"));
    if (bytes->find("KHR_draco_mesh_compression") != std::string::npos)
      *bytes = binary ? place_draco_accessors_in_glb(*bytes) : place_draco_accessors(*bytes);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(keep_image_bytes, nullptr);
    loader.SetFsCallbacks(
        {&file_exists, &tinygltf::ExpandFilePath, &read_whole_regular_file, &tinygltf::WriteWholeFile, nullptr});
    tinygltf::Model model;
    std::string err, warn;
    const std::string base_dir = std::filesystem::path(path).parent_path().string();
    const auto* data = reinterpret_cast<const unsigned char*>(bytes->data());
    const auto size = static_cast<unsigned int>(bytes->size());
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, base_dir)
                           : loader.LoadASCIIFromString(&model, &err, &warn, bytes->data(), size, base_dir);
    std::vector<std::string> warnings = lines_of(warn);
    for (std::string& line : warnings) line = without_data_uris(line);
    for (const std::string& line : warnings) result.warnings.push_back(path + ": " + line);
    std::vector<std::string> errors = lines_of(err);
    for (std::string& line : errors) {
      line = without_data_uris(line);
      // nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
      if (line.rfind("[json.exception.", 0) == 0 && line.find("] ") != std::string::npos)
        line = "invalid JSON: " + json_parse_reason(line.substr(line.find("] ") + 2));
      // tinygltf's "File not found : x.bin", for buffers
      if (line.rfind("File not found : ", 0) == 0)
        line = "cannot read '" + line.substr(17) + "' (a buffer the file names)";
    }
    if (!ok) {
      std::string what;
      for (const std::string& line : errors) what += (what.empty() ? "" : "; ") + line;
      throw load_error(path + ": " + (what.empty() ? "not a glTF file" : what));
    }
    for (const std::string& line : errors) result.warnings.push_back(path + ": " + line);
    gltf_reader reader{path, model, materials, textures, result};
    reader.read();
    return result;
  } catch (load_error& e) {
    e.warnings.insert(e.warnings.begin(), result.warnings.begin(), result.warnings.end());
    throw;
  }
}

}  // namespace bounce
