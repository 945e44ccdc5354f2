// assimp_loader.cpp - every other format Assimp reads (FBX, COLLADA, 3DS, OFF, X3D, 3MF, ...): meshes and nodes.
#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/file_util.hpp"
#include "facet/error.hpp"
#include "facet/model.hpp"
#include "job/io/assimp_animation.hpp"
#include "job/io/loaders.hpp"
#include "job/shared_library.hpp"

namespace facet {
namespace {

// Assimp's C functions facet calls. Assimp is opened on the first model it reads, not linked: mapping, relocating
// and constructing it (with the minizip it brings) added 5 ms to the 17 ms start of every facet process. Its C
// interface, unlike the C++ one, can be called through pointers looked up by name.
// clang-format off
#define FACET_ASSIMP_FUNCTIONS(X) \
  X(aiCreatePropertyStore) X(aiSetImportPropertyInteger) X(aiReleasePropertyStore) \
  X(aiImportFileExWithProperties) X(aiReleaseImport) X(aiGetErrorString) X(aiIsExtensionSupported) \
  X(aiGetMaterialColor) X(aiGetMaterialFloatArray) X(aiGetMaterialString) X(aiGetMaterialTexture)
// clang-format on

struct AssimpApi {
#define FACET_DECLARE(name) decltype(&::name) name = nullptr;
  FACET_ASSIMP_FUNCTIONS(FACET_DECLARE)
#undef FACET_DECLARE
};

#define FACET_TEXT(x) #x
#define FACET_NUMBER_TEXT(x) FACET_TEXT(x)

// The table, filled on first use from the soname of the Assimp facet was built with (FACET_ASSIMP_MAJOR, from
// CMake: libassimp.so.5 for Assimp 5). Throws std::runtime_error naming the missing library and its package; a
// later call tries again.
const AssimpApi& assimp() {
  static const AssimpApi table = [] {
    const SharedLibrary library("libassimp.so." FACET_NUMBER_TEXT(FACET_ASSIMP_MAJOR),
                                "libassimp" FACET_NUMBER_TEXT(FACET_ASSIMP_MAJOR));
    AssimpApi a;
#define FACET_RESOLVE(name) a.name = library.function<decltype(&::name)>(#name);
    FACET_ASSIMP_FUNCTIONS(FACET_RESOLVE)
#undef FACET_RESOLVE
    return a;
  }();
  return table;
}

glm::vec4 color_of(const aiMaterial& m, const char* key, unsigned type, unsigned index, glm::vec4 fallback) {
  aiColor4D c;
  if (assimp().aiGetMaterialColor(&m, key, type, index, &c) != AI_SUCCESS) return fallback;
  const glm::vec4 v(c.r, c.g, c.b, c.a);
  const bool finite = std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b) && std::isfinite(v.a);
  return finite ? glm::clamp(v, glm::vec4(0.0f), glm::vec4(1.0f)) : fallback;
}

std::optional<float> float_of(const aiMaterial& m, const char* key, unsigned type, unsigned index) {
  ai_real value = 0;
  if (assimp().aiGetMaterialFloatArray(&m, key, type, index, &value, nullptr) != AI_SUCCESS) return std::nullopt;
  return static_cast<float>(value);
}

Material material_of(const aiMaterial& m, const ReferencePolicy& policy, const LoadOptions& options,
                     const std::string& source) {
  const AssimpApi& ai = assimp();
  Material out;
  aiString name;
  if (ai.aiGetMaterialString(&m, AI_MATKEY_NAME, &name) == AI_SUCCESS) out.name = printable(name.C_Str());
  out.diffuse = color_of(m, AI_MATKEY_COLOR_DIFFUSE, glm::vec4(1.0f));
  const std::optional<float> opacity = float_of(m, AI_MATKEY_OPACITY);
  if (opacity && std::isfinite(*opacity)) out.diffuse.a = std::clamp(*opacity, 0.0f, 1.0f);
  out.specular = glm::vec3(color_of(m, AI_MATKEY_COLOR_SPECULAR, glm::vec4(0.0f)));
  const std::optional<float> shininess = float_of(m, AI_MATKEY_SHININESS);
  if (shininess && std::isfinite(*shininess) && *shininess > 0.0f) out.shininess = std::min(*shininess, 1024.0f);
  aiString texture;
  // Embedded textures ("*0") are not read; a file is found as the policy allows.
  if (ai.aiGetMaterialTexture(&m, aiTextureType_DIFFUSE, 0, &texture, nullptr, nullptr, nullptr, nullptr, nullptr,
                              nullptr) == AI_SUCCESS &&
      texture.length > 0 && texture.C_Str()[0] != '*') {
    const std::string what = "texture '" + printable(texture.C_Str()) + "' of material '" + out.name + "'";
    out.diffuse_texture = usable_texture(policy, options, texture.C_Str(), what, source).value_or("");
  }
  return out;
}

// The files Assimp opens for a model: the model itself, and the companions it names (materials, parts, skeletons)
// only as the reference policy allows, regular files only. Assimp joins a companion's name to the model's folder
// (or passes an absolute name as it is); the part after the folder is the name the model wrote. Assimp asks
// whether a file exists by opening and closing it.
class ConfinedFiles {
 public:
  ConfinedFiles(const std::filesystem::path& model, ReferencePolicy policy)
      : model_(model.lexically_normal()), policy_(std::move(policy)) {}

  // The callbacks Assimp's C interface calls, this object their user data: it outlives the import.
  aiFileIO io() const { return aiFileIO{open, close, reinterpret_cast<char*>(const_cast<ConfinedFiles*>(this))}; }

 private:
  // An open file: the callbacks first (Assimp is handed a pointer to them), then the stream they read.
  struct OpenFile {
    aiFile callbacks;
    std::FILE* stream;
    std::size_t size;
  };

  std::optional<std::filesystem::path> where(const char* file) const {
    const std::filesystem::path asked = std::filesystem::path(file).lexically_normal();
    if (asked == model_) return model_;
    const std::string folder = policy_.folder.lexically_normal().string();
    std::string name = asked.string();
    if (!folder.empty() && folder != "." && name.starts_with(folder + "/")) name.erase(0, folder.size() + 1);
    return resolve_reference(policy_, name).path;
  }

  // Assimp's C code calls these, so no exception leaves them: a file that cannot be opened is not there.
  static aiFile* open(aiFileIO* io, const char* file, const char* mode) noexcept {
    try {
      if (!file || !mode || std::string_view(mode).find_first_of("wa+") != std::string_view::npos) return nullptr;
      const std::optional<std::filesystem::path> path =
          reinterpret_cast<const ConfinedFiles*>(io->UserData)->where(file);
      if (!path) return nullptr;
      auto opened = std::make_unique<OpenFile>(OpenFile{{read, write, tell, size, seek, flush, nullptr}, nullptr, 0});
      // Opened as the model was (read_regular_file): without waiting, then checked, so that a FIFO or device put
      // in a regular file's place since it was resolved is not read either.
      int fd;
      do fd = ::open(path->c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
      while (fd < 0 && errno == EINTR);
      if (fd < 0) return nullptr;
      struct stat info {};
      if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode) || !(opened->stream = ::fdopen(fd, "rb"))) {
        ::close(fd);
        return nullptr;
      }
      opened->size = static_cast<std::size_t>(info.st_size);
      return &opened.release()->callbacks;
    } catch (...) {
      return nullptr;
    }
  }
  static void close(aiFileIO*, aiFile* file) noexcept {
    OpenFile* opened = of(file);
    std::fclose(opened->stream);
    delete opened;
  }
  // callbacks is OpenFile's first member, so the two share an address.
  static OpenFile* of(aiFile* file) { return reinterpret_cast<OpenFile*>(file); }
  static std::size_t read(aiFile* file, char* buffer, std::size_t size, std::size_t count) noexcept {
    return std::fread(buffer, size, count, of(file)->stream);
  }
  static std::size_t write(aiFile*, const char*, std::size_t, std::size_t) noexcept { return 0; }
  static std::size_t tell(aiFile* file) noexcept { return static_cast<std::size_t>(::ftello(of(file)->stream)); }
  static std::size_t size(aiFile* file) noexcept { return of(file)->size; }
  // Assimp passes a backward step as a size_t that wraps, as its own reader (fseek with a long) takes it.
  static aiReturn seek(aiFile* file, std::size_t offset, aiOrigin origin) noexcept {
    const int whence = origin == aiOrigin_CUR ? SEEK_CUR : origin == aiOrigin_END ? SEEK_END : SEEK_SET;
    return ::fseeko(of(file)->stream, static_cast<off_t>(offset), whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
  }
  static void flush(aiFile*) noexcept {}

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
  return !extension.empty() && assimp().aiIsExtensionSupported(extension.c_str()) == AI_TRUE;
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
  const AssimpApi& ai = assimp();
  const ConfinedFiles files(path, policy);
  aiFileIO io = files.io();
  const std::unique_ptr<aiPropertyStore, decltype(ai.aiReleasePropertyStore)> properties(ai.aiCreatePropertyStore(),
                                                                                         ai.aiReleasePropertyStore);
  // Lines and points are dropped by the sort; the node tree is walked below, as the glTF reader walks its nodes.
  ai.aiSetImportPropertyInteger(properties.get(), AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags =
      aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
  std::unique_ptr<const aiScene, decltype(ai.aiReleaseImport)> scene(nullptr, ai.aiReleaseImport);
  std::string error;
  {
    // Assimp's C interface keeps the error of the last failed import in one string for the whole process: imports
    // take turns (facet batch loads on several threads), so that none writes it while another does or reads it.
    static std::mutex importing;
    const std::lock_guard<std::mutex> hold(importing);
    // From the path rather than the bytes already read: many of these formats name companion files (materials,
    // skeletons, external parts) that Assimp opens beside the model.
    scene.reset(ai.aiImportFileExWithProperties(path.string().c_str(), flags, &io, properties.get()));
    if (!scene) error = ai.aiGetErrorString();
  }
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
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
  struct Pending {
    const aiNode* node;
    glm::mat4 parent;
    std::int32_t parent_id;
  };
  std::vector<Pending> pending{{scene->mRootNode, glm::mat4(1.0f), -1}};
  std::vector<const aiNode*> walked;  // by id
  std::vector<std::int32_t> parents;
  std::uint32_t node_number = 0;
  while (!pending.empty()) {
    const auto [node, parent, parent_id] = pending.back();
    pending.pop_back();
    const std::uint32_t id = node_number++;
    walked.push_back(node);
    parents.push_back(parent_id);
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
      out.instances.push_back(ModelInstance{slot, world, id, static_cast<std::int32_t>(id)});
    }
    for (unsigned c = node->mNumChildren; c-- > 0;)
      if (node->mChildren[c]) pending.push_back({node->mChildren[c], world, static_cast<std::int32_t>(id)});
  }
  if (out.instances.empty()) throw InputError(source, "no triangles found");
  read_assimp_motion(*scene, walked, parents, slots, out, source);
  return out;
}

}  // namespace facet
