// model_io.hpp - reading model files: Wavefront OBJ (with its MTL materials), PLY, STL, glTF 2.0 and Assimp's formats.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "facet/mesh.hpp"
#include "facet/model.hpp"

namespace facet {

// Files larger than this are refused before reading (1 GiB).
inline constexpr std::uintmax_t kMaxModelFileBytes = std::uintmax_t{1} << 30;
// The default of LoadOptions::max_triangles.
inline constexpr std::uint64_t kDefaultMaxTriangles = 100'000'000;
// The largest triangle limit a face accepts (2^40): beyond any file, and far below overflow in the loaders' counts.
inline constexpr std::uint64_t kMostMaxTriangles = std::uint64_t{1} << 40;
// The default of LoadOptions::max_points, and the largest a face accepts (as for triangles).
inline constexpr std::uint64_t kDefaultMaxPoints = 100'000'000;
inline constexpr std::uint64_t kMostMaxPoints = std::uint64_t{1} << 40;

// What reading a model may do. Model files are untrusted input (a thumbnailer renders what users upload): these
// bound what one can make facet read and allocate.
struct LoadOptions {
  // Read the files a model names (MTL libraries, textures, glTF buffers and images, the parts Assimp's formats name)
  // wherever they are. When false, only from inside the model's folder tree: a name that is absolute or climbs out
  // (../) is looked for by its file name in the model's folder, as viewers do for models made on another machine,
  // and a link leading out of the tree is not followed. Either way only regular files are read, never a device,
  // FIFO or directory.
  bool allow_external_files = false;
  // Models whose instances place more triangles than this are refused.
  std::uint64_t max_triangles = kDefaultMaxTriangles;
  // Models whose instances place more points and Gaussian splats together than this are refused.
  std::uint64_t max_points = kDefaultMaxPoints;
  // Textures wider or taller than this (at most kMaxTextureSize, 16384) are not decoded: the material is drawn
  // untextured, with a warning.
  int max_texture_size = 16384;
  // Threads a reader may use for one large file (an ASCII PLY's body is parsed in two halves); 0: as many as the
  // machine has cores.
  int threads = 0;
};

// Reads a model file into a Model (model.hpp): its indexed, triangulated, validated meshes in their own
// coordinates, the instances placing them (at least one triangle in all) and its cameras. The reader is chosen by
// the (case-insensitive) extension, ".obj", ".ply", ".stl", ".gltf", ".glb", or one Assimp reads; a file with another
// extension or none is
// recognised by its content ("ply" magic line, GLB magic, glTF JSON, a binary STL's size, "solid", or OBJ
// statements after any comments). Polygons are
// triangulated as fans (c0 c1 c2), (c0 c2 c3), ... when convex and ear-clipped when concave, corner order kept;
// triangles stay in file order.
//   OBJ: one vertex per distinct position/uv/normal reference.
//     - normals / uvs: kept only if every face corner references one (else empty: the renderer derives them);
//     - colors: kept only if every `v` line carries r g b (else empty);
//     - materials from the MTL files (Kd + d -> diffuse, Ks -> specular, Ns -> shininess, map_Kd ->
//       diffuse_texture, resolved against the .obj's folder, '\' read as '/'); face_materials is filled (with -1
//       for faces without a known material) when the file has materials, else left empty;
//     - faces with fewer than 3 corners, points and lines are dropped.
//   PLY (ascii, binary_little_endian, binary_big_endian 1.0): the `vertex` element's x y z, nx ny nz (normals),
//     red green blue [alpha] or diffuse_red ... (colors: integer types scaled by their maximum, e.g. uchar / 255,
//     floats as they are, alpha 1 if absent) and s t, u v, texture_u texture_v or texture_s texture_t (uvs), each
//     kept when the file has it; the `face` element's `vertex_indices` (or `vertex_index`) list of any integer
//     types, faces with fewer than 3 corners dropped. Vertices are not merged. Other elements and properties are
//     skipped; a file with vertices but no faces (a point cloud) is refused.
//   STL (binary, or ASCII with one or more solids): exactly equal positions are welded into one vertex (+0 and -0
//     alike), numbered in order of first use; facet normals and colours are ignored (normals left empty).
//   glTF 2.0 (.gltf with external or data: buffers and images, .glb), through tinygltf: the default scene (else
//     every root node), each node that places a mesh an instance with its matrix or TRS composed down the
//     hierarchy; triangles, strips and fans of every primitive, indexed or not;
//     NORMAL, TEXCOORD_0 and COLOR_0 of any component type, sparse accessors; one material per glTF material
//     (the metallic-roughness inputs, emission and occlusion; linear factors encoded as displayed; textures
//     decoded), the specification's default material for primitives without one; Draco- and meshopt-compressed
//     data decoded; the cameras the scene's nodes place (Mesh::cameras). Points and lines are skipped with a
//     warning; an extension the file lists as required that facet does not implement (it implements
//     KHR_mesh_quantization, KHR_texture_transform, KHR_materials_unlit, KHR_materials_emissive_strength,
//     KHR_draco_mesh_compression and EXT_meshopt_compression) is refused naming it.
//   Other formats, through Assimp (triangulated, points and lines dropped): each aiMesh with its material, placed
//     by the nodes of the scene's node tree.
// Every reader records where each triangle came from: Mesh::face_ids numbers the file's faces (OBJ `f` lines of
// 3+ corners; PLY faces; glTF triangles per mesh; Assimp triangles per mesh), a polygon's triangles sharing one
// (empty where every face is one triangle); ModelInstance::id names the glTF node, or the Assimp node, placing it.
// Throws InputError(path, problem) with a one-line problem, naming the line (text) or byte offset (binary) where
// that helps, for: no such file, not a regular file, an empty or too large file, an unsupported format, a file
// that does not parse or ends early, counts that do not fit in the file, references to vertices/uvs/normals that
// do not exist, non-finite positions (and, in PLY, non-finite normals, colours or uvs), polygons with more corners
// than supported (OBJ 255, PLY 1024), or no triangles at all.
// A missing MTL file, a missing texture file (diffuse_texture is then left empty), dropped faces, unknown PLY header
// lines and data after a PLY's last element only print a one-line "facet: warning: ..." to stderr.
// Refuses a model placing more than options.max_triangles triangles, and applies the other LoadOptions.
Model read_model(const std::filesystem::path& path, const LoadOptions& options = {});
// The same, also naming the reader that read it: "OBJ", "PLY", "STL", "glTF", "GLB" or "Assimp (ext)".
Model read_model(const std::filesystem::path& path, std::string& format, const LoadOptions& options = {});

// read_model(path) flattened into one world-space mesh (flatten in model.hpp), with the file's cameras and each
// triangle's instance id in Mesh::instance_ids: what `facet render` draws.
Mesh load_model(const std::filesystem::path& path, const LoadOptions& options = {});
Mesh load_model(const std::filesystem::path& path, std::string& format, const LoadOptions& options = {});

}  // namespace facet
