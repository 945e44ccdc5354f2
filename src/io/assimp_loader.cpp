// assimp_loader.cpp - every other format Assimp reads (FBX, COLLADA, 3DS, OFF, X3D, 3MF, ...), as one mesh.
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "facet/error.hpp"
#include "io/loaders.hpp"

namespace facet {
namespace {

// Assimp's loaders expand some files a great deal (instanced nodes, tessellated surfaces): past this many
// vertices the model is refused rather than allowed to take the machine's memory.
constexpr std::size_t kMaxVertices = std::size_t{1} << 27;

glm::vec4 color_of(const aiMaterial& m, const char* key, unsigned type, unsigned index, glm::vec4 fallback) {
  aiColor4D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  const glm::vec4 v(c.r, c.g, c.b, c.a);
  const bool finite = std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b) && std::isfinite(v.a);
  return finite ? glm::clamp(v, glm::vec4(0.0f), glm::vec4(1.0f)) : fallback;
}

Material material_of(const aiMaterial& m, const std::filesystem::path& folder) {
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
  // Embedded textures ("*0") are not read; a file path is resolved against the model's folder.
  if (m.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS && texture.length > 0 &&
      texture.C_Str()[0] != '*') {
    std::string file = texture.C_Str();
    std::replace(file.begin(), file.end(), '\\', '/');
    out.diffuse_texture = (folder / file).lexically_normal().string();
  }
  return out;
}

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

Mesh load_with_assimp(const std::filesystem::path& path, std::string_view bytes, const std::string& source) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".off") check_off_counts(bytes, source);
  Assimp::Importer importer;
  // Lines and points are dropped by the sort; the pre-transform flattens the node hierarchy into world space,
  // as the glTF reader does.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices |
                         aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
  // From the path rather than the bytes already read: many of these formats name companion files (materials,
  // skeletons, external parts) that Assimp opens beside the model.
  const aiScene* scene = importer.ReadFile(path.string(), flags);
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    std::string error = importer.GetErrorString();
    error = error.substr(0, error.find('\n'));
    throw InputError(source, "Assimp cannot read it (" + printable(error.empty() ? "no scene" : error) + ")");
  }

  Mesh out;
  const std::filesystem::path folder = path.parent_path();
  for (unsigned i = 0; i < scene->mNumMaterials; ++i)
    out.materials.push_back(material_of(*scene->mMaterials[i], folder));
  bool all_normals = true, any_uvs = false, any_colors = false;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh& m = *scene->mMeshes[i];
    if (!(m.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || m.mNumVertices == 0) continue;
    const std::size_t base = out.positions.size();
    if (m.mNumVertices > kMaxVertices - base) throw InputError(source, "the model expands to more than 2^27 vertices");
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      out.positions.emplace_back(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
      out.normals.push_back(m.mNormals ? glm::vec3(m.mNormals[v].x, m.mNormals[v].y, m.mNormals[v].z)
                                       : glm::vec3(0, 0, 1));
      out.uvs.push_back(m.mTextureCoords[0] ? glm::vec2(m.mTextureCoords[0][v].x, m.mTextureCoords[0][v].y)
                                            : glm::vec2(0));
      const aiColor4D* c = m.mColors[0];
      out.colors.push_back(c ? glm::vec4(c[v].r, c[v].g, c[v].b, c[v].a) : glm::vec4(1.0f));
    }
    all_normals = all_normals && m.mNormals;
    any_uvs = any_uvs || m.mTextureCoords[0];
    any_colors = any_colors || m.mColors[0];
    const int material = m.mMaterialIndex < out.materials.size() ? static_cast<int>(m.mMaterialIndex) : -1;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const aiFace& face = m.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= m.mNumVertices)
          throw InputError(source, "mesh " + std::to_string(i) + " face " + std::to_string(f) + " index " +
                                       std::to_string(face.mIndices[k]) + " is out of range");
        out.indices.push_back(static_cast<std::uint32_t>(base + face.mIndices[k]));
      }
      out.face_materials.push_back(material);
      out.face_ids.push_back(f);
      out.instance_ids.push_back(i);
    }
  }
  if (out.indices.empty()) throw InputError(source, "no triangles found");
  // Non-finite normals are replaced rather than refused: the renderer recomputes them when a mesh has none.
  for (const glm::vec3& n : out.normals)
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) all_normals = false;
  if (!all_normals) out.normals.clear();
  if (!any_uvs) out.uvs.clear();
  if (!any_colors) out.colors.clear();
  validate(out, source);
  return out;
}

}  // namespace facet
