#include "scene/assimp_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>

namespace bounce {
namespace {

// assimp's logger is one per process: one import at a time holds it, and
// its warnings and errors are collected here.
std::mutex logger_mutex;

class collecting_stream : public Assimp::LogStream {
 public:
  explicit collecting_stream(std::vector<std::string>& lines) : lines_(lines) {}
  void write(const char* message) override {
    std::string line(message);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    // "Warn,  T0: text" -> "text"
    if (const std::size_t colon = line.find(": "); colon != std::string::npos && colon < 16) line.erase(0, colon + 2);
    if (!line.empty()) lines_.push_back(line);
  }

 private:
  std::vector<std::string>& lines_;
};

// A file stream that gives up when the importer keeps reading or seeking
// without end: assimp 5.2's PLY reader loops for ever on a header without
// end_header, seeking to the end and reading nothing. A parser reads a file
// a few times over at most; past a budget of calls in proportion to the
// size, the stream throws, and assimp turns that into a failed import.
class guarded_stream : public Assimp::IOStream {
 public:
  // Owns `inner`: assimp deletes some streams itself rather than through
  // the IO system's Close.
  explicit guarded_stream(Assimp::IOStream* inner)
      : inner_(inner), budget_((std::size_t(1) << 16) + 4 * inner->FileSize()) {}
  ~guarded_stream() override { delete inner_; }
  guarded_stream(const guarded_stream&) = delete;
  guarded_stream& operator=(const guarded_stream&) = delete;
  size_t Read(void* buffer, size_t size, size_t count) override {
    spend();
    return inner_->Read(buffer, size, count);
  }
  size_t Write(const void* buffer, size_t size, size_t count) override { return inner_->Write(buffer, size, count); }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    spend();
    return inner_->Seek(offset, origin);
  }
  size_t Tell() const override { return inner_->Tell(); }
  size_t FileSize() const override { return inner_->FileSize(); }
  void Flush() override { inner_->Flush(); }

 private:
  void spend() {
    if (++calls_ > budget_)
      throw std::runtime_error("the importer read the file over and over without end (a truncated or broken file?)");
  }
  Assimp::IOStream* inner_;
  std::size_t budget_;
  std::size_t calls_ = 0;
};

class guarded_files : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    note_input_file(file);
    Assimp::IOStream* inner = DefaultIOSystem::Open(file, mode);
    return inner ? new guarded_stream(inner) : nullptr;
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool finite_within(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::abs(v.x) <= max_file_number &&
         std::abs(v.y) <= max_file_number && std::abs(v.z) <= max_file_number;
}

struct reader {
  const std::string& path;
  const aiScene& in;
  std::vector<material>& materials;
  std::vector<texture>& textures;
  assimp_read_result& result;
  std::set<std::string> warned;
  std::map<std::pair<unsigned, bool>, int> material_of;  // (assimp material, with texture) -> scene material
  std::map<std::string, int> texture_of;                 // texture reference -> scene texture

  void warn_once(const std::string& kind, const std::string& text) {
    if (warned.insert(kind).second) result.warnings.push_back(path + ": " + text);
  }

  // The scene texture of a diffuse texture reference ("*0" for an embedded
  // one, else a file beside the model), or -1 with a warning.
  int diffuse_texture(const std::string& reference, const std::string& who) {
    if (auto it = texture_of.find(reference); it != texture_of.end()) return it->second;
    int index = -1;
    try {
      if (const aiTexture* embedded = in.GetEmbeddedTexture(reference.c_str())) {
        if (embedded->mHeight != 0) {
          warn_once("raw texture", who + ": uncompressed embedded textures are not read; the material is untextured");
        } else {
          const std::string_view bytes(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
          textures.push_back(decode_image_texture(bytes, reference, path + ": " + who, "embedded texture"));
          index = int(textures.size()) - 1;
        }
      } else {
        const std::string file = resolve(path, reference);
        textures.push_back(read_image_texture(file, reference, path + ": " + who));
        index = int(textures.size()) - 1;
      }
    } catch (const load_error& e) {
      // A missing texture leaves its material plain, as a viewer would show it.
      warn_once("texture " + reference, std::string(e.what()) + "; the material is drawn without it");
    }
    texture_of[reference] = index;
    return index;
  }

  int scene_material(unsigned index, bool textured) {
    if (auto it = material_of.find({index, textured}); it != material_of.end()) return it->second;
    material out;
    const aiMaterial* m = index < in.mNumMaterials ? in.mMaterials[index] : nullptr;
    const std::string where = "material " + std::to_string(index);
    aiString name;
    if (m && m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0) out.name = name.C_Str();
    const std::string who = where + (out.name.empty() ? "" : " '" + out.name + "'");
    if (out.name.empty()) out.name = where;
    aiColor3D diffuse(0.5f, 0.5f, 0.5f), emissive(0.0f, 0.0f, 0.0f);
    if (!m || m->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != AI_SUCCESS)
      warn_once("no diffuse", who + ": no diffuse colour; grey (rho 0.5) is used");
    if (m) m->Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    rgb rho(diffuse.r, diffuse.g, diffuse.b), ke(emissive.r, emissive.g, emissive.b);
    if (!std::isfinite(rho.r + rho.g + rho.b) || glm::any(glm::lessThan(rho, rgb(0.0))) ||
        glm::any(glm::greaterThan(rho, rgb(max_colour_channel))))
      throw load_error(path + ": " + who + ": diffuse colour " + format_value(rho) +
                       " is not a reflectance (channels go from 0 to 1)");
    bool clamped = false;
    for (int c = 0; c < 3; ++c)
      if (rho[c] >= 1.0) {
        rho[c] = max_reflectance;
        clamped = true;
      }
    if (clamped)
      warn_once("clamped " + who, who + ": diffuse colour channels of 1 or more are read as " +
                                      format_value(max_reflectance) + " (a reflectance of 1 creates light)");
    if (!std::isfinite(ke.r + ke.g + ke.b) || glm::any(glm::lessThan(ke, rgb(0.0))) ||
        glm::any(glm::greaterThan(ke, rgb(max_file_number))))
      throw load_error(path + ": " + who + ": emissive colour " + format_value(ke) +
                       " must be finite and not negative");
    out.rho = rho;
    out.ke = ke;
    int two_sided = 0;
    if (m && m->Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) out.two_sided = two_sided != 0;
    aiString reference;
    if (m && m->GetTexture(aiTextureType_DIFFUSE, 0, &reference) == AI_SUCCESS && reference.length > 0) {
      if (textured)
        out.texture = diffuse_texture(reference.C_Str(), who);
      else
        warn_once("texture without uvs", who + ": a mesh without texture coordinates draws it untextured");
    }
    aiColor3D specular(0.0f, 0.0f, 0.0f);
    float opacity = 1.0f;
    if (m && m->Get(AI_MATKEY_COLOR_SPECULAR, specular) == AI_SUCCESS && (specular.r + specular.g + specular.b) > 0.0f)
      warn_once("specular", who + ": specular colours ignored (and in every other material): surfaces are diffuse");
    if (m && m->Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f)
      warn_once("opacity", who + ": opacity below 1 ignored (and in every other material): surfaces are opaque");
    materials.push_back(out);
    const int made = int(materials.size()) - 1;
    material_of[{index, textured}] = made;
    return made;
  }

  void read_mesh(const aiMesh& mesh, unsigned number) {
    const std::string who =
        "mesh " + std::to_string(number) + (mesh.mName.length ? " '" + std::string(mesh.mName.C_Str()) + "'" : "");
    if (mesh.mVertices == nullptr || mesh.mNumVertices == 0) return;
    if (mesh.HasVertexColors(0))
      warn_once("vertex colours", who + ": vertex colours ignored (and in every other mesh)");
    polygon_mesh out;
    out.positions.reserve(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!finite_within(p))
        throw load_error(path + ": " + who + ": vertex " + std::to_string(v) + " is not finite or beyond 1e9");
      out.positions.emplace_back(p.x, p.y, p.z);
    }
    const bool has_normals = mesh.mNormals != nullptr;
    if (has_normals)
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& n = mesh.mNormals[v];
        out.normals.push_back(std::isfinite(n.x + n.y + n.z) ? vec3(n.x, n.y, n.z) : vec3(0.0));
      }
    const bool has_uvs = mesh.HasTextureCoords(0);
    if (has_uvs)
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& t = mesh.mTextureCoords[0][v];
        out.uvs.emplace_back(std::isfinite(t.x) ? t.x : 0.0, std::isfinite(t.y) ? t.y : 0.0);
      }
    const int material_index = scene_material(mesh.mMaterialIndex, has_uvs);
    std::size_t dropped_lines = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) {
        ++dropped_lines;
        continue;
      }
      if (face.mNumIndices > max_face_corners)
        throw load_error(path + ": " + who + ": face " + std::to_string(f) + " has " +
                         std::to_string(face.mNumIndices) + " corners (at most " + std::to_string(max_face_corners) +
                         ")");
      polygon_face pf;
      pf.material = material_index;
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const unsigned i = face.mIndices[k];
        if (i >= mesh.mNumVertices)
          throw load_error(path + ": " + who + ": face " + std::to_string(f) + " names vertex " + std::to_string(i) +
                           " of " + std::to_string(mesh.mNumVertices));
        pf.position.push_back(int(i));
        if (has_normals) pf.normal.push_back(int(i));
        if (has_uvs) pf.uv.push_back(int(i));
      }
      out.faces.push_back(std::move(pf));
    }
    if (dropped_lines > 0)
      warn_once("points and lines", who + ": " + std::to_string(dropped_lines) +
                                        " points and lines dropped (and in any other mesh): only faces are surfaces");
    if (out.faces.empty()) return;
    surface s;
    s.name = mesh.mName.length ? mesh.mName.C_Str() : "mesh " + std::to_string(number);
    s.geometry = std::move(out);
    result.surfaces.push_back(std::move(s));
  }
};

}  // namespace

bool read_through_assimp(const std::string& path) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  return std::find(std::begin(assimp_extensions), std::end(assimp_extensions), ext) != std::end(assimp_extensions);
}

assimp_read_result read_assimp(const std::string& path, std::vector<material>& materials,
                               std::vector<texture>& textures) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw load_error(path + ": cannot read the file (not a regular file)");
  assimp_read_result result;
  std::vector<std::string> logged;
  const std::lock_guard lock(logger_mutex);
  Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
  collecting_stream* stream = new collecting_stream(logged);  // the logger owns and deletes it
  Assimp::DefaultLogger::get()->attachStream(stream, Assimp::Logger::Warn | Assimp::Logger::Err);
  struct logger_guard {
    ~logger_guard() { Assimp::DefaultLogger::kill(); }
  } guard;
  Assimp::Importer importer;
  importer.SetIOHandler(new guarded_files);  // the importer owns and deletes it
  // Points and lines are dropped by the importer; faces stay polygons.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* in = importer.ReadFile(path, aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices |
                                                  aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  auto with_log = [&](load_error e) {
    for (const std::string& line : logged) e.warnings.push_back(path + ": assimp: " + line);
    return e;
  };
  if (!in || !in->mRootNode || (in->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    const std::string why = importer.GetErrorString();
    throw with_log(load_error(path + ": cannot read the model (assimp: " + (why.empty() ? "no scene" : why) + ")"));
  }
  reader r{path, *in, materials, textures, result, {}, {}, {}};
  try {
    for (unsigned i = 0; i < in->mNumMeshes; ++i)
      if (in->mMeshes[i]) r.read_mesh(*in->mMeshes[i], i);
  } catch (load_error& e) {
    throw with_log(std::move(e));
  }
  if (in->mNumCameras > 0) r.warn_once("cameras", "cameras ignored: the view is fitted to the model");
  if (in->mNumLights > 0)
    r.warn_once("lights", std::to_string(in->mNumLights) +
                              " light(s) ignored: Bounce's lights are emitting surfaces "
                              "and point lights of a JSON scene");
  if (in->mNumAnimations > 0) r.warn_once("animations", "animations ignored: the model is read at rest");
  for (const std::string& line : logged) result.warnings.push_back(path + ": assimp: " + line);
  if (result.surfaces.empty()) throw load_error(path + ": the model has no faces");
  return result;
}

}  // namespace bounce
