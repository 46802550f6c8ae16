// glTF files built in memory for the tests: a document and its one binary
// buffer, written as .gltf (the buffer as a base64 data URI) or as .glb.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace bounce::test_support {

inline std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = std::uint8_t(bytes[i]) << 16 | std::uint8_t(bytes[i + 1]) << 8 | std::uint8_t(bytes[i + 2]);
    for (int k = 18; k >= 0; k -= 6) out += table[(v >> k) & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t v = std::uint8_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= std::uint8_t(bytes[i + 1]) << 8;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// A glTF document and its one binary buffer, built up piece by piece.
struct gltf_file {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  int view(const void* data, std::size_t n) {
    while (bin.size() % 4) bin += '\0';
    const std::size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), n);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", n}});
    return int(doc["bufferViews"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const char* type, int components) {
    const int bv = view(v.data(), v.size() * sizeof(float));
    doc["accessors"].push_back(
        {{"bufferView", bv}, {"componentType", 5126}, {"count", v.size() / components}, {"type", type}});
    return int(doc["accessors"].size()) - 1;
  }
  int indices(const std::vector<std::uint16_t>& v) {
    const int bv = view(v.data(), v.size() * sizeof(std::uint16_t));
    doc["accessors"].push_back({{"bufferView", bv}, {"componentType", 5123}, {"count", v.size()}, {"type", "SCALAR"}});
    return int(doc["accessors"].size()) - 1;
  }
  int material(const nlohmann::json& m) {
    doc["materials"].push_back(m);
    return int(doc["materials"].size()) - 1;
  }
  // A vector, not a json: `json{object}` would copy the object, not make an array.
  int mesh(const std::vector<nlohmann::json>& primitives) {
    doc["meshes"].push_back({{"primitives", primitives}});
    return int(doc["meshes"].size()) - 1;
  }
  int node(const nlohmann::json& n) {
    doc["nodes"].push_back(n);
    return int(doc["nodes"].size()) - 1;
  }
  // Each node listed becomes a root of scene 0.
  void roots(const std::vector<int>& nodes) { doc["scenes"] = {{{"nodes", nodes}}}; }

  std::string gltf_text() const {
    nlohmann::json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
    return d.dump();
  }
  std::string glb() const {
    nlohmann::json d = doc;
    d["buffers"] = {{{"byteLength", bin.size()}}};
    std::string text = d.dump();
    while (text.size() % 4) text += ' ';
    std::string payload = bin;
    while (payload.size() % 4) payload += '\0';
    auto u32 = [](std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    return "glTF" + u32(2) + u32(std::uint32_t(12 + 8 + text.size() + 8 + payload.size())) +
           u32(std::uint32_t(text.size())) + "JSON" + text + u32(std::uint32_t(payload.size())) + "BIN" +
           std::string(1, '\0') + payload;
  }
};

}  // namespace bounce::test_support
