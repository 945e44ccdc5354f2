// loaders.hpp - the model readers behind read_model() (OBJ, PLY, STL, glTF, Assimp) and the helpers they share.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "facet/mesh.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/warnings.hpp"
#include "core/file_util.hpp"
#include "job/io/references.hpp"

namespace facet {

// Each reader gets the model's path (OBJ resolves its MTL and texture files against it), the whole file read once
// by read_model (non-empty, at most kMaxModelFileBytes) and the source name for its InputErrors. Each returns a
// validated mesh (or model, each of its meshes validated) with at least one triangle or point placed, or throws
// InputError(source, one-line problem).
// The readers of formats that name other files read them as options allow (references.hpp).
Mesh load_obj(const std::filesystem::path& path, std::string_view bytes, const std::string& source,
              const LoadOptions& options);
// An ASCII PLY body of one entry per line, from two_from bytes on, is parsed in two halves by two threads when
// `threads` (0: the machine's cores) allows; the mesh, warnings and errors are the same either way. *in_two, if
// given, tells whether it was.
constexpr std::size_t kPlyTwoThreadsFrom = std::size_t{1} << 20;
Mesh load_ply(std::string_view bytes, const std::string& source, int threads = 1,
              std::size_t two_from = kPlyTwoThreadsFrom, bool* in_two = nullptr);
Mesh load_stl(std::string_view bytes, const std::string& source);
// A point cloud as text, one point per line: x y z, then optionally r g b (0..255 or 0..1) or nx ny nz (told apart
// by whether every row's three are unit vectors), intensity r g b (Leica's .pts), or both colours and normals.
// Numbers are separated by spaces, tabs, commas or semicolons; blank lines and lines starting with # or // are
// skipped, and a first line of one number (a point count) too.
Mesh load_xyz(std::string_view bytes, const std::string& source);
// A Point Cloud Library PCD file (ascii, binary or binary_compressed data): x y z, normal_x normal_y normal_z and a
// packed rgb or rgba where it has them; other fields are skipped, and so are points whose position is NaN (an
// organized cloud's missing points), with a warning.
Mesh load_pcd(std::string_view bytes, const std::string& source);
// glTF resolves external buffers and images against the path's folder; its meshes and node instances.
Model load_gltf(const std::filesystem::path& path, std::string_view bytes, const std::string& source,
                const LoadOptions& options);

// Every other format Assimp reads, its meshes and node instances; Assimp opens the file (and its companions) itself.
Model load_with_assimp(const std::filesystem::path& path, std::string_view bytes, const std::string& source,
                       const LoadOptions& options);

// The texture file a material names, if it can be used: a regular file found as `policy` allows whose image is at
// most options.max_texture_size a side; otherwise nullopt, after a warning naming `what` (e.g. "texture 'a.png'
// of material 'm'"). Only the image's header is read here; it is decoded when drawn.
std::optional<std::string> usable_texture(const ReferencePolicy& policy, const LoadOptions& options,
                                          std::string_view name, const std::string& what, const std::string& source);
// Makes each vertex's skin weights (d.influences a vertex) sum to 1: negative and non-finite ones become 0 and the
// rest are scaled; a vertex of no weight keeps none (it follows its node). Warns once for each, naming `what` (the
// mesh) and how many vertices were mended.
void normalise_skin_weights(MeshDeformation& d, const std::string& what, const std::string& source);

// Whether Assimp has a reader for this extension (".fbx", with the dot).
bool assimp_reads(const std::string& extension);

// A GLB file starts with the magic "glTF".
bool is_gltf_binary(std::string_view bytes);

// A binary STL is recognised by its size: an 80-byte header, a little-endian uint32 triangle count, 50 bytes per
// triangle, nothing after. Its header may begin with "solid" like an ASCII STL, so this is asked first.
bool is_binary_stl(std::string_view bytes);

// Numbers a mesh's triangles by the file's faces as they are appended, filling Mesh::face_ids only once some face
// does not become exactly one triangle (a polygon, or a face dropped): until then the ids are the triangle indices.
class FaceNumbering {
 public:
  // After appending the face's triangles; `triangles_before` is the triangle count before them.
  void add_face(Mesh& mesh, std::size_t triangles_before) {
    const std::size_t now = mesh.indices.size() / 3;
    if (mesh.face_ids.empty()) {
      if (face_ == triangles_before && now == triangles_before + 1) {
        ++face_;
        return;
      }
      mesh.face_ids.resize(triangles_before);
      for (std::size_t t = 0; t < triangles_before; ++t) mesh.face_ids[t] = static_cast<std::uint32_t>(t);
    }
    mesh.face_ids.insert(mesh.face_ids.end(), now - triangles_before, face_++);
  }
  // A face that became no triangle still takes its number.
  void drop_face() { ++face_; }

 private:
  std::uint32_t face_ = 0;
};

// Text from the file shortened to 200 characters, control characters replaced, fit for a one-line message.
std::string printable(std::string_view s);

// The warning "<source>: <message>" (facet/warnings.hpp).
void warn(const std::string& source, const std::string& message);

}  // namespace facet
