// gltf_primitive.hpp - one glTF primitive's vertex arrays, read from accessors or decoded from Draco.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
}  // namespace tinygltf

namespace facet {

// Each optional array is empty when the primitive has no such attribute.
struct PrimitiveArrays {
  std::vector<float> positions;  // 3 per vertex
  std::vector<float> normals;    // 3 per vertex
  std::vector<float> uvs;        // 2 per vertex (TEXCOORD_0)
  std::vector<float> uvs1;       // 2 per vertex (TEXCOORD_1)
  std::vector<float> tangents;   // 4 per vertex (TANGENT)
  std::vector<float> colors;     // color_components per vertex (COLOR_0)
  int color_components = 4;
  bool indexed = false;
  std::vector<std::uint32_t> corners;  // the index list when indexed, in the primitive's mode (list, strip, fan)
};

// Decodes a primitive compressed with KHR_draco_mesh_compression through Draco: its POSITION, NORMAL, TEXCOORD_0
// and COLOR_0 (normalized integers scaled to 0..1 or -1..1) and its triangles. Throws InputError(source, ...) for
// a missing or out-of-range buffer view, data Draco cannot decode, a point cloud, attribute ids the data does not
// hold, or more than max_vertices points.
PrimitiveArrays decode_draco(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                             std::size_t max_vertices, const std::string& source);

// The file with its JSON text rewritten, for tinygltf: `rewrite` gets the JSON and whether it came from a GLB, and
// returns the new JSON or nullopt to leave it. The result is the new .gltf text or the GLB with its JSON chunk
// replaced, or nullopt when nothing changes (or the GLB's header cannot be read, or its sizes do not agree with the
// file's: tinygltf then reports it).
using JsonRewrite = std::optional<std::string> (*)(std::string_view json, bool binary);
std::optional<std::string> with_gltf_json_rewritten(std::string_view bytes, bool binary, JsonRewrite rewrite);

// tinygltf built without Draco (as Debian's is) refuses a primitive whose index accessor has no buffer view, which
// is how Draco-compressed primitives list theirs. Their indices come from the Draco data, so the file is handed to
// tinygltf with those "indices" removed: the rewritten .gltf text or GLB file, or nullopt when nothing changes.
std::optional<std::string> without_draco_indices(std::string_view bytes, bool binary);

}  // namespace facet
