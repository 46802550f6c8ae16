#include "scene/draco_mesh.h"

#include <draco/compression/decode.h>

namespace bounce {

std::string decode_draco_mesh(std::string_view bytes, const std::map<int, int>& wanted, draco_mesh& out) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) return "not a Draco stream (" + type.status().error_msg_string() + ")";
  if (type.value() != draco::TRIANGULAR_MESH) return "a Draco point cloud, not a mesh";
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return "the Draco stream does not decode (" + decoded.status().error_msg_string() + ")";
  const draco::Mesh& mesh = *decoded.value();
  out = {};
  out.points = mesh.num_points();
  out.triangles.reserve(mesh.num_faces());
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(f);
    out.triangles.push_back({int(face[0].value()), int(face[1].value()), int(face[2].value())});
  }
  for (const auto& [id, components] : wanted) {
    const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(std::uint32_t(id));
    if (!attribute) return "the Draco stream has no attribute " + std::to_string(id);
    if (attribute->num_components() < components || components > 4)
      return "Draco attribute " + std::to_string(id) + " has " + std::to_string(attribute->num_components()) +
             " components, not " + std::to_string(components);
    std::vector<double>& values = out.attributes[id];
    values.resize(out.points * std::size_t(components));
    float v[4] = {0, 0, 0, 0};
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
      if (!attribute->ConvertValue<float>(attribute->mapped_index(p), std::int8_t(components), v))
        return "Draco attribute " + std::to_string(id) + " cannot be read as numbers";
      for (int c = 0; c < components; ++c) values[std::size_t(p.value()) * std::size_t(components) + c] = v[c];
    }
  }
  return {};
}

}  // namespace bounce
