// glTF 2.0 reader (.gltf with its buffers and images, or .glb) on Debian's
// tinygltf, which parses the JSON and fetches the bytes. tinygltf trusts
// the file's indices and byte ranges; this reader checks every one, so a
// bad file gets a message naming the file and the mesh, primitive or
// accessor, never a read out of bounds.
#pragma once

#include <string>
#include <vector>

#include "scene/reader_support.h"  // load_error
#include "scene/scene.h"

namespace bounce {

// A metallic-roughness material is a mirror when metallicFactor is at least
// this and roughnessFactor at most the next (glTF's defaults, 1 and 1, are a
// rough metal: diffuse). A mirror's kr is metallicFactor x base colour.
inline constexpr double gltf_mirror_metallic = 0.5;
inline constexpr double gltf_mirror_roughness = 0.25;

struct gltf_read_result {
  std::vector<surface> surfaces;       // one polygon mesh per node that holds a mesh
  std::vector<punctual_light> lights;  // KHR_lights_punctual, placed by their nodes
  std::vector<std::string> warnings;
};

// Reads `path` (the scene's default scene, or scene 0): triangles with
// their node transforms applied, base colour as rho (texture included),
// smooth metals as mirrors, transmission as glass, emission as ke (its
// texture as emission_texture), KHR_lights_punctual lights, Draco meshes.
// New materials and textures are appended to the lists and faces refer to
// them by index. What Bounce cannot use (rough metals, normal maps,
// cameras, animation, ...) gets one warning per kind. Throws load_error.
gltf_read_result read_gltf(const std::string& path, std::vector<material>& materials, std::vector<texture>& textures);

}  // namespace bounce
