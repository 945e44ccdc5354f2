// model_io.cpp - load_model(): checks and reads a model file once, then hands it to its reader.
#include "facet/model_io.hpp"

#include <algorithm>
#include <cctype>
#include <new>
#include <string>
#include <string_view>
#include <utility>

#include "core/file_util.hpp"
#include "facet/error.hpp"
#include "facet/splats.hpp"
#include "job/io/loaders.hpp"
#include "job/io/splat_loader.hpp"
#include "job/io/text_scan.hpp"

namespace facet {

namespace fs = std::filesystem;

std::string printable(std::string_view s) {
  std::string out(s.substr(0, 200));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

void warn(const std::string& source, const std::string& message) { warn(source + ": " + message); }

namespace {

enum class Format { kObj, kPly, kStl, kGltf, kXyz, kPcd, kSplat, kAssimp, kUnknown };

// A build without Assimp (the browser page's, FACET_NO_ASSIMP) reads facet's own formats alone.
#ifndef FACET_NO_ASSIMP
constexpr const char* kSupported =
    "supported: .obj, .ply, .stl, .gltf, .glb, .xyz, .pts, .pcd, .splat and the formats Assimp reads";
#else
constexpr const char* kSupported = "supported: .obj, .ply, .stl, .gltf, .glb, .xyz, .pts, .pcd and .splat";
#endif

Format format_of_extension(const std::string& extension) {
  if (extension == ".obj") return Format::kObj;
  if (extension == ".ply") return Format::kPly;
  if (extension == ".stl") return Format::kStl;
  if (extension == ".gltf" || extension == ".glb") return Format::kGltf;
  if (extension == ".xyz" || extension == ".pts") return Format::kXyz;
  if (extension == ".pcd") return Format::kPcd;
  if (extension == ".splat") return Format::kSplat;
#ifndef FACET_NO_ASSIMP
  if (assimp_reads(extension)) return Format::kAssimp;
#endif
  return Format::kUnknown;
}

// OBJ has no magic number: the first line that is neither blank nor a comment must start with an OBJ statement.
bool looks_like_obj(std::string_view bytes) {
  constexpr std::string_view kStatements[] = {"v", "vt", "vn", "f", "o", "g", "s", "mtllib", "usemtl"};
  bool comments = false;
  std::size_t pos = 0;
  for (int lines = 0; pos < bytes.size() && lines < 1000; ++lines) {
    const std::size_t end = std::min(bytes.find('\n', pos), bytes.size());
    std::string_view line = bytes.substr(pos, end - pos);
    pos = end + 1;
    while (!line.empty() && is_space(line.front())) line.remove_prefix(1);
    if (line.empty()) continue;
    if (line.front() == '#') {
      comments = true;
      continue;
    }
    std::size_t word = 0;
    while (word < line.size() && !is_space(line[word])) ++word;
    if (word == line.size()) return false;  // a statement takes at least one argument
    return std::find(std::begin(kStatements), std::end(kStatements), line.substr(0, word)) != std::end(kStatements);
  }
  return comments && pos >= bytes.size();  // only comments: an OBJ with nothing in it
}

// glTF JSON: an object whose text names its required "asset" member near the start.
bool looks_like_gltf_json(std::string_view bytes) {
  std::size_t first = 0;
  while (first < bytes.size() && is_space(bytes[first])) ++first;
  return first < bytes.size() && bytes[first] == '{' &&
         bytes.substr(0, 4096).find("\"asset\"") != std::string_view::npos;
}

// For files whose extension names no supported format: magic numbers first, then the shape of the text.
Format format_of_content(std::string_view bytes) {
  if (bytes.starts_with("ply\n") || bytes.starts_with("ply\r\n")) return Format::kPly;
  if (bytes.starts_with("# .PCD") || bytes.starts_with("VERSION")) return Format::kPcd;
  if (is_gltf_binary(bytes) || looks_like_gltf_json(bytes)) return Format::kGltf;
  if (is_binary_stl(bytes)) return Format::kStl;
  if (bytes.starts_with("solid") && (bytes.size() == 5 || is_space(bytes[5]))) return Format::kStl;
  if (looks_like_obj(bytes)) return Format::kObj;
  return Format::kUnknown;
}

// A format without nodes: its one mesh, placed once where it is.
Model one_mesh(Mesh mesh) {
  Model model;
  model.meshes.push_back(std::move(mesh));
  model.instances.push_back(ModelInstance{});
  return model;
}

// Reads the file with the reader its extension or content names.
Model read_any_model(const fs::path& path, std::string& format_name, const LoadOptions& options) {
  const std::string source = path.string();
  const std::string extension = path.extension().string();
  Format format = format_of_extension(lower_extension(path));
  FileBytes bytes = read_regular_file(path, kMaxModelFileBytes, source);
  if (format == Format::kUnknown) format = format_of_content(bytes);
  constexpr const char* kNames[] = {"OBJ", "PLY", "STL", "glTF", "XYZ", "PCD", "splat", "Assimp", ""};
  format_name = kNames[static_cast<int>(format)];
  if (format == Format::kGltf && is_gltf_binary(bytes)) format_name = "GLB";
  if (format == Format::kAssimp) format_name += " (" + printable(extension.substr(1)) + ")";
  try {
    switch (format) {
      case Format::kObj: return one_mesh(load_obj(path, bytes, source, options));
      case Format::kPly: return one_mesh(load_ply(bytes, source, options.threads));
      case Format::kStl: return one_mesh(load_stl(bytes, source));
      case Format::kGltf: return load_gltf(path, bytes, source, options);
      case Format::kXyz: return one_mesh(load_xyz(bytes, source));
      case Format::kPcd: return one_mesh(load_pcd(bytes, source));
      case Format::kSplat: return one_mesh(load_splat(bytes, source));
#ifndef FACET_NO_ASSIMP
      case Format::kAssimp: return load_with_assimp(path, bytes, source, options);
#else
      case Format::kAssimp: break;
#endif
      case Format::kUnknown: break;
    }
  } catch (const std::bad_alloc&) {
    throw InputError(source, "out of memory while loading");
  }
  if (extension.empty())
    throw InputError(source, std::string("unsupported model format (no file extension; ") + kSupported + ")");
  throw InputError(source, "unsupported model format '" + printable(extension) + "' (" + kSupported + ")");
}

}  // namespace

Model read_model(const fs::path& path, const LoadOptions& options) {
  std::string format;
  return read_model(path, format, options);
}

Model read_model(const fs::path& path, std::string& format_name, const LoadOptions& options) {
  Model model = read_any_model(path, format_name, options);
  std::uint64_t triangles = 0, points = 0;
  for (const ModelInstance& instance : model.instances) {
    const Mesh& mesh = model.meshes[instance.mesh];
    triangles += mesh.indices.size() / 3;
    points += mesh.points.size() + (mesh.splats ? mesh.splats->size() : 0);
  }
  if (triangles > options.max_triangles)
    throw InputError(path.string(), "places " + std::to_string(triangles) + " triangles, more than the limit of " +
                                        std::to_string(options.max_triangles) + " (" + setting("max_triangles") + ")");
  if (points > options.max_points)
    throw InputError(path.string(), "places " + std::to_string(points) + " points and splats, more than the limit of " +
                                        std::to_string(options.max_points) + " (" + setting("max_points") + ")");
  return model;
}

Mesh load_model(const fs::path& path, const LoadOptions& options) {
  std::string format;
  return load_model(path, format, options);
}

Mesh load_model(const fs::path& path, std::string& format_name, const LoadOptions& options) {
  Model model = read_model(path, format_name, options);
  try {
    // Skins and morph weights deform the meshes even at rest, as every glTF viewer draws them.
    return flatten(at_rest(std::move(model), path.string(), options.threads), path.string());
  } catch (const std::bad_alloc&) {
    throw InputError(path.string(), "out of memory while loading");
  }
}

}  // namespace facet
