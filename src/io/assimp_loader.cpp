// assimp_loader.cpp - every other format Assimp reads (FBX, COLLADA, 3DS, OFF, X3D, 3MF, ...): meshes and nodes.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/DefaultIOSystem.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "facet/error.hpp"
#include "facet/model.hpp"
#include "io/file_util.hpp"
#include "io/loaders.hpp"

namespace facet {
namespace {

glm::vec4 color_of(const aiMaterial& m, const char* key, unsigned type, unsigned index, glm::vec4 fallback) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  const glm::vec4 v(c.r, c.g, c.b, c.a);
  const bool finite = std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b) && std::isfinite(v.a);
  return finite ? glm::clamp(v, glm::vec4(0.0f), glm::vec4(1.0f)) : fallback;
}

Material material_of(const aiMaterial& m, const ReferencePolicy& policy, const LoadOptions& options,
                     const std::string& source) {
  Material out;
  aiString name;
  if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = printable(name.C_Str());
  out.diffuse = color_of(m, AI_MATKEY_COLOR_DIFFUSE, glm::vec4(1.0f));
  float opacity = 1.0f;
  if (m.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && std::isfinite(opacity))
    out.diffuse.a = std::clamp(opacity, 0.0f, 1.0f);
  out.specular = glm::vec3(color_of(m, AI_MATKEY_COLOR_SPECULAR, glm::vec4(0.0f)));
  float shininess = 0.0f;
  if (m.Get(AI_MATKEY_SHININESS, shininess) == AI_SUCCESS && std::isfinite(shininess) && shininess > 0.0f)
    out.shininess = std::min(shininess, 1024.0f);
  aiString texture;
  // Embedded textures ("*0") are not read; a file is found as the policy allows.
  if (m.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS && texture.length > 0 &&
      texture.C_Str()[0] != '*') {
    const std::string what = "texture '" + printable(texture.C_Str()) + "' of material '" + out.name + "'";
    out.diffuse_texture = usable_texture(policy, options, texture.C_Str(), what, source).value_or("");
  }
  return out;
}

// The files Assimp opens for a model: the model itself, and the companions it names (materials, parts, skeletons)
// only as the reference policy allows, regular files only. Assimp joins a companion's name to the model's folder
// (or passes an absolute name as it is); the part after the folder is the name the model wrote.
class ConfinedIoSystem final : public Assimp::DefaultIOSystem {
 public:
  ConfinedIoSystem(std::filesystem::path model, ReferencePolicy policy)
      : model_(model.lexically_normal()), policy_(std::move(policy)) {}

  bool Exists(const char* file) const override { return where(file).has_value(); }

  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return nullptr;
    const std::optional<std::filesystem::path> path = where(file);
    return path ? DefaultIOSystem::Open(path->c_str(), mode) : nullptr;
  }

 private:
  std::optional<std::filesystem::path> where(const char* file) const {
    const std::filesystem::path asked = std::filesystem::path(file).lexically_normal();
    if (asked == model_) return model_;
    const std::string folder = policy_.folder.lexically_normal().string();
    std::string name = asked.string();
    if (!folder.empty() && folder != "." && name.starts_with(folder + "/")) name.erase(0, folder.size() + 1);
    return resolve_reference(policy_, name).path;
  }

  std::filesystem::path model_;
  ReferencePolicy policy_;
};

// Assimp's OFF reader believes the header's counts: 3.5e13 vertices in a 309-byte file keep it busy for good. An
// ASCII vertex takes at least 6 bytes ("0 0 0\n") and a face 8 ("3 0 1 2\n"), so counts the file cannot hold are
// refused first. Binary OFF ("OFF BINARY") is not read by Assimp at all.
void check_off_counts(std::string_view bytes, const std::string& source) {
  std::size_t pos = 0;
  const auto next_token = [&]() -> std::string_view {
    for (;;) {
      while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
      if (pos < bytes.size() && bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
        continue;
      }
      const std::size_t start = pos;
      while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
      return bytes.substr(start, pos - start);
    }
  };
  const std::string_view keyword = next_token();
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return;
  double counts[2] = {0, 0};
  for (double& count : counts) {
    const std::string_view token = next_token();
    if (std::from_chars(token.data(), token.data() + token.size(), count).ec != std::errc()) return;
  }
  if (counts[0] * 6 + counts[1] * 8 > static_cast<double>(bytes.size())) {
    char text[96];
    std::snprintf(text, sizeof text, "%.0f vertices, %.0f faces", counts[0], counts[1]);
    throw InputError(source, std::string("the OFF header's counts (") + text + ") do not fit in its " +
                                 std::to_string(bytes.size()) + " bytes");
  }
}

}  // namespace

bool assimp_reads(const std::string& extension) {
  return !extension.empty() && Assimp::Importer().IsExtensionSupported(extension);
}

namespace {

// One aiMesh as an object-space Mesh with its one material; an empty mesh when it holds no triangles.
Mesh mesh_of(const aiMesh& m, unsigned index, const std::vector<Material>& materials, const std::string& source) {
  Mesh out;
  if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || m.mNumVertices == 0) return out;
  if (m.mNumVertices > kMaxModelVertices) throw InputError(source, "a mesh has more than 2^27 vertices");
  bool finite_normals = m.mNormals != nullptr;
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    out.positions.emplace_back(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
    if (m.mNormals) {
      const glm::vec3 n(m.mNormals[v].x, m.mNormals[v].y, m.mNormals[v].z);
      finite_normals = finite_normals && std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z);
      out.normals.push_back(n);
    }
    if (m.mTextureCoords[0]) out.uvs.emplace_back(m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y);
    if (const aiColor4D* c = m.mColors[0]) out.colors.emplace_back(c[v].r, c[v].g, c[v].b, c[v].a);
  }
  // Non-finite normals are dropped rather than refused: the renderer derives normals for a mesh that has none.
  if (!finite_normals) out.normals.clear();
  const bool has_material = m.mMaterialIndex < materials.size();
  if (has_material) out.materials.push_back(materials[m.mMaterialIndex]);
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) continue;
    for (unsigned k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= m.mNumVertices)
        throw InputError(source, "mesh " + std::to_string(index) + " face " + std::to_string(f) + " index " +
                                     std::to_string(face.mIndices[k]) + " is out of range");
      out.indices.push_back(face.mIndices[k]);
    }
    if (has_material) out.face_materials.push_back(0);
    out.face_ids.push_back(f);
  }
  validate(out, source);
  return out;
}

glm::mat4 matrix_of(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major (a1 a2 a3 a4 is the first row); glm is column-major.
  return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

}  // namespace

Model load_with_assimp(const std::filesystem::path& path, std::string_view bytes, const std::string& source,
                       const LoadOptions& options) {
  if (lower_extension(path) == ".off") check_off_counts(bytes, source);
  const ReferencePolicy policy{path.parent_path(), options.allow_external_files};
  Assimp::Importer importer;
  importer.SetIOHandler(new ConfinedIoSystem(path, policy));  // the importer owns and deletes it
  // Lines and points are dropped by the sort; the node tree is walked below, as the glTF reader walks its nodes.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags =
      aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
  // From the path rather than the bytes already read: many of these formats name companion files (materials,
  // skeletons, external parts) that Assimp opens beside the model.
  const aiScene* scene = importer.ReadFile(path.string(), flags);
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    std::string error = importer.GetErrorString();
    error = error.substr(0, error.find('\n'));
    throw InputError(source, "Assimp cannot read it (" + printable(error.empty() ? "no scene" : error) + ")");
  }

  std::vector<Material> materials;
  for (unsigned i = 0; i < scene->mNumMaterials; ++i)
    materials.push_back(material_of(*scene->mMaterials[i], policy, options, source));
  Model out;
  constexpr std::uint32_t kUnread = 0xFFFFFFFFu, kNoTriangles = 0xFFFFFFFEu;
  std::vector<std::uint32_t> slots(scene->mNumMeshes, kUnread);  // per aiMesh: its index in out.meshes
  std::size_t expanded = 0;
  // Depth first, parents before children, with a stack of its own: a file can nest nodes deeper than a thread's
  // stack would allow recursion to.
  std::vector<std::pair<const aiNode*, glm::mat4>> pending{{scene->mRootNode, glm::mat4(1.0f)}};
  std::uint32_t node_number = 0;
  while (!pending.empty()) {
    const auto [node, parent] = pending.back();
    pending.pop_back();
    const std::uint32_t id = node_number++;
    if (id == kNoSurface) throw InputError(source, "the scene has more nodes than 32-bit ids can number");
    const glm::mat4 world = parent * matrix_of(node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned index = node->mMeshes[k];
      if (index >= scene->mNumMeshes)
        throw InputError(source, "a node places mesh " + std::to_string(index) + ", which does not exist");
      std::uint32_t& slot = slots[index];
      if (slot == kUnread) {
        Mesh mesh = mesh_of(*scene->mMeshes[index], index, materials, source);
        slot = mesh.indices.empty() ? kNoTriangles : static_cast<std::uint32_t>(out.meshes.size());
        if (!mesh.indices.empty()) out.meshes.push_back(std::move(mesh));
      }
      if (slot == kNoTriangles) continue;
      const std::size_t count = out.meshes[slot].vertex_count();
      if (count > kMaxModelVertices - expanded)
        throw InputError(source, "the model expands to more than 2^27 vertices");
      expanded += count;
      out.instances.push_back(ModelInstance{slot, world, id});
    }
    for (unsigned c = node->mNumChildren; c-- > 0;)
      if (node->mChildren[c]) pending.emplace_back(node->mChildren[c], world);
  }
  if (out.instances.empty()) throw InputError(source, "no triangles found");
  return out;
}

}  // namespace facet
