// gltf_loader.cpp - glTF 2.0 (.gltf with its buffers and images, .glb) through tinygltf: the default scene's meshes.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "core/file_util.hpp"
#include "facet/color.hpp"
#include "facet/error.hpp"
#include "facet/model.hpp"
#include "facet/texture.hpp"
#include "job/io/gltf_accessors.hpp"
#include "job/io/gltf_animation.hpp"
#include "job/io/gltf_lights.hpp"
#include "job/io/gltf_material.hpp"
#include "job/io/gltf_meshopt.hpp"
#include "job/io/gltf_primitive.hpp"
#include "job/io/loaders.hpp"
#include "scene/texture/image_decode.hpp"

namespace facet {
namespace {

// Required extensions facet implements: the reader handles any component type, so quantized attributes
// (KHR_mesh_quantization) read like floats; texture transforms are applied to TEXCOORD_0 (KHR_texture_transform);
// unlit materials draw with their colour alone (KHR_materials_unlit); the material extensions facet shades are
// read (ior, specular, clearcoat, sheen, and transmission as docs/FORMATS.md approximates it); emission is scaled
// (KHR_materials_emissive_strength); Draco-compressed primitives are decoded
// (KHR_draco_mesh_compression), and so are compressed buffer views where meshoptimizer is built in
// (EXT_meshopt_compression).
const std::set<std::string> kSupportedRequired = {"KHR_mesh_quantization",      "KHR_texture_transform",
                                                  "KHR_materials_unlit",        "KHR_materials_emissive_strength",
                                                  "KHR_materials_ior",          "KHR_materials_specular",
                                                  "KHR_materials_clearcoat",    "KHR_materials_sheen",
                                                  "KHR_materials_transmission", "KHR_lights_punctual",
                                                  "KHR_draco_mesh_compression",
#ifndef FACET_NO_MESHOPT
                                                  "EXT_meshopt_compression"
#endif
};

glm::mat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[static_cast<std::size_t>(i)]);
    return m;
  }
  glm::mat4 m(1.0f);
  if (node.translation.size() == 3)
    m[3] = glm::vec4(static_cast<float>(node.translation[0]), static_cast<float>(node.translation[1]),
                     static_cast<float>(node.translation[2]), 1.0f);
  if (node.rotation.size() == 4) {
    const glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                      static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
    m = m * glm::mat4_cast(glm::normalize(q));
  }
  if (node.scale.size() == 3)
    m = m * glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                                  static_cast<float>(node.scale[2])));
  return m;
}

// Walks the scene's nodes: each glTF mesh a node places is read once into an object-space Mesh, each such node
// becomes an instance.
class SceneReader {
 public:
  SceneReader(const tinygltf::Model& model, const std::string& source)
      : model_(model), reader_{model, source}, deformation_(reader_), slots_(model.meshes.size(), kUnread) {
    std::set<int> warned_textures;
    for (const tinygltf::Material& m : model.materials) {
      uv_transforms_.push_back(uv_transform_of(m.pbrMetallicRoughness.baseColorTexture, source));
      materials_.push_back(material_of(model_, m, source, warned_textures));
    }
    uv_transforms_.emplace_back(1.0f);
    materials_.push_back(default_material());  // for primitives without a material
  }

  void node(int index, const glm::mat4& parent, int depth) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      reader_.fail("node " + std::to_string(index) + " does not exist");
    if (on_path_.count(index)) reader_.fail("node " + std::to_string(index) + " is its own ancestor");
    if (depth > 64)
      reader_.fail("the node hierarchy is more than 64 levels deep (at node " + std::to_string(index) + ")");
    const tinygltf::Node& n = model_.nodes[static_cast<std::size_t>(index)];
    const glm::mat4 world = parent * local_transform(n);
    if (n.mesh >= 0) place(n.mesh, world, index, n.skin);
    if (n.camera >= 0) {
      camera(n.camera, world);
      out_.camera_nodes.push_back(index);
    }
    if (std::optional<Light> light = light_of(model_, n, world, reader_.source, warned_lights_)) {
      out_.lights.push_back(std::move(*light));
      out_.light_nodes.push_back(index);
    }
    on_path_.insert(index);
    for (int child : n.children) node(child, world, depth + 1);
    on_path_.erase(index);
  }

  Model finish() {
    if (out_.instances.empty()) reader_.fail("the default scene has no triangles and no points");
    out_.nodes = read_nodes(reader_);
    out_.skins = read_skins(reader_);
    out_.animations = read_animations(reader_);
    if (std::all_of(out_.deformations.begin(), out_.deformations.end(),
                    [](const MeshDeformation& d) { return d.empty(); }))
      out_.deformations.clear();
    return std::move(out_);
  }

 private:
  static constexpr std::uint32_t kUnread = 0xFFFFFFFFu, kNoTriangles = 0xFFFFFFFEu;

  // Each node placing a mesh is an instance (its node index). Instancing can multiply a small file's triangles, so
  // the vertices the scene expands to are counted as it is walked, and a graph that would pass the limit is refused.
  void place(int index, const glm::mat4& world, int node, int skin) {
    if (static_cast<std::size_t>(index) >= model_.meshes.size())
      reader_.fail("mesh " + std::to_string(index) + " does not exist");
    std::uint32_t& slot = slots_[static_cast<std::size_t>(index)];
    if (slot == kUnread) slot = read_mesh(index);
    if (slot == kNoTriangles) return;
    const std::size_t count = out_.meshes[slot].vertex_count();
    if (count > kMaxModelVertices - expanded_) reader_.fail("the scene expands to more than 2^27 vertices");
    expanded_ += count;
    if (skin >= 0 && static_cast<std::size_t>(skin) >= model_.skins.size())
      reader_.fail("node " + std::to_string(node) + "'s skin " + std::to_string(skin) + " does not exist");
    out_.instances.push_back(ModelInstance{slot, world, static_cast<std::uint32_t>(node), node, skin});
  }

  // The mesh's triangles are numbered across its primitives, in order; its materials are those its primitives use.
  std::uint32_t read_mesh(int index) {
    mesh_ = Mesh{};
    local_materials_.assign(materials_.size(), -1);
    all_normals_ = true;
    any_uvs_ = any_uvs1_ = any_tangents_ = any_colors_ = false;
    std::uint32_t face = 0;
    deformation_.start(index);
    for (const tinygltf::Primitive& p : model_.meshes[static_cast<std::size_t>(index)].primitives) primitive(p, face);
    if (mesh_.indices.empty() && mesh_.points.empty()) return kNoTriangles;
    if (!all_normals_) mesh_.normals.clear();
    if (!any_uvs_) mesh_.uvs.clear();
    if (!any_uvs1_) mesh_.uvs1.clear();
    if (!any_tangents_ || !all_normals_) mesh_.tangents.clear();  // glTF ignores tangents where normals are missing
    if (!any_colors_) mesh_.colors.clear();
    if (std::all_of(mesh_.face_materials.begin(), mesh_.face_materials.end(), [](int m) { return m < 0; }))
      mesh_.face_materials.clear();
    validate(mesh_, reader_.source);
    out_.deformations.push_back(deformation_.finish());
    out_.meshes.push_back(std::move(mesh_));
    return static_cast<std::uint32_t>(out_.meshes.size() - 1);
  }

  // A camera as its node places it. The spec allows no scale on camera nodes; any is removed, keeping the
  // rotation and position, so the view matrix stays rigid.
  void camera(int index, const glm::mat4& world) {
    if (static_cast<std::size_t>(index) >= model_.cameras.size())
      reader_.fail("camera " + std::to_string(index) + " does not exist");
    const tinygltf::Camera& c = model_.cameras[static_cast<std::size_t>(index)];
    ModelCamera out;
    out.name = c.name;
    out.perspective = c.type != "orthographic";
    if (out.perspective) {
      out.yfov_radians = static_cast<float>(c.perspective.yfov);
      out.znear = static_cast<float>(c.perspective.znear);
      if (c.perspective.zfar > 0.0) out.zfar = static_cast<float>(c.perspective.zfar);
    } else {
      out.magnification = glm::vec2(static_cast<float>(c.orthographic.xmag), static_cast<float>(c.orthographic.ymag));
      out.znear = static_cast<float>(c.orthographic.znear);
      out.zfar = static_cast<float>(c.orthographic.zfar);
    }
    out.world_from_camera = rigid_camera_pose(world);
    out_.cameras.push_back(std::move(out));
  }

  // The primitive's arrays from its accessors; each attribute must have one element per position.
  PrimitiveArrays accessor_arrays(const tinygltf::Primitive& p) const {
    const auto attribute = [&](const char* name) {
      const auto it = p.attributes.find(name);
      return it == p.attributes.end() ? -1 : it->second;
    };
    if (attribute("POSITION") < 0) reader_.fail("a primitive has no POSITION attribute");
    PrimitiveArrays out;
    out.positions = reader_.floats(attribute("POSITION"), 3, "POSITION");
    if (attribute("NORMAL") >= 0) out.normals = reader_.floats(attribute("NORMAL"), 3, "NORMAL");
    if (attribute("TEXCOORD_0") >= 0) out.uvs = reader_.floats(attribute("TEXCOORD_0"), 2, "TEXCOORD_0");
    if (attribute("TEXCOORD_1") >= 0) out.uvs1 = reader_.floats(attribute("TEXCOORD_1"), 2, "TEXCOORD_1");
    if (attribute("TANGENT") >= 0) out.tangents = reader_.floats(attribute("TANGENT"), 4, "TANGENT");
    if (const int colors = attribute("COLOR_0"); colors >= 0) {
      const int type = reader_.model.accessors.at(static_cast<std::size_t>(colors)).type;
      out.color_components = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
      out.colors = reader_.floats(colors, out.color_components, "COLOR_0");
    }
    if (p.indices >= 0) {
      out.indexed = true;
      out.corners = reader_.indices(p.indices);
    }
    return out;
  }

  void primitive(const tinygltf::Primitive& p, std::uint32_t& face) {
    const bool draco = p.extensions.count("KHR_draco_mesh_compression") > 0;
    const bool points = !draco && p.mode == TINYGLTF_MODE_POINTS;
    if (!draco && !points && p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      if (!warned_lines_) warn(reader_.source, "lines are not drawn; skipping those primitives");
      warned_lines_ = true;
      return;
    }
    const std::size_t base = mesh_.positions.size();
    // Draco decodes to a triangle list whatever the primitive's mode.
    PrimitiveArrays data =
        draco ? decode_draco(model_, p, kMaxModelVertices - base, reader_.source) : accessor_arrays(p);
    const std::size_t count = data.positions.size() / 3;
    if (count > kMaxModelVertices - base) reader_.fail("a mesh has more than 2^27 vertices");
    const auto check_count = [&](const std::vector<float>& values, std::size_t components, const char* name) {
      if (!values.empty() && values.size() != count * components)
        reader_.fail(std::string(name) + " has " + std::to_string(values.size() / components) + " elements but " +
                     "POSITION has " + std::to_string(count));
    };
    check_count(data.normals, 3, "NORMAL");
    check_count(data.uvs, 2, "TEXCOORD_0");
    check_count(data.uvs1, 2, "TEXCOORD_1");
    check_count(data.tangents, 4, "TANGENT");
    check_count(data.colors, static_cast<std::size_t>(data.color_components), "COLOR_0");

    std::vector<std::uint32_t>& corners = data.corners;
    if (!data.indexed) {
      corners.resize(count);
      for (std::size_t i = 0; i < count; ++i) corners[i] = static_cast<std::uint32_t>(i);
    }
    for (std::uint32_t c : corners)
      if (c >= count)
        reader_.fail("index " + std::to_string(c) + " is out of range (" + std::to_string(count) + " vertices)");
    if (!draco && p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) corners = triangles_from_strip(corners);
    if (!draco && p.mode == TINYGLTF_MODE_TRIANGLE_FAN) corners = triangles_from_fan(corners);
    if (!points) corners.resize(corners.size() / 3 * 3);

    const std::vector<float>& positions = data.positions;
    for (std::size_t i = 0; i < count; ++i)
      mesh_.positions.emplace_back(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    append_normals(data.normals, count);
    append_tangents(data.tangents, count);
    const int material = p.material >= 0 && static_cast<std::size_t>(p.material) < model_.materials.size()
                             ? p.material
                             : static_cast<int>(model_.materials.size());  // the default material
    // The base colour texture's transform goes to the set it reads (KHR_texture_transform is read for it alone).
    const glm::mat3& transform = uv_transforms_[static_cast<std::size_t>(material)];
    const bool base_on_set1 = materials_[static_cast<std::size_t>(material)].uv1_maps & texture_slot::base_color;
    append_uvs(mesh_.uvs, any_uvs_, data.uvs, count, base_on_set1 ? glm::mat3(1.0f) : transform);
    append_uvs(mesh_.uvs1, any_uvs1_, data.uvs1, count, base_on_set1 ? transform : glm::mat3(1.0f));
    append_colors(data.colors, data.color_components, count);
    deformation_.primitive(p, count, draco);

    // A POINTS primitive's corners are points; they take the mesh's default material (and their vertex colours).
    if (points) {
      for (const std::uint32_t c : corners) mesh_.points.push_back(static_cast<std::uint32_t>(base) + c);
      return;
    }
    const std::int32_t local = local_material(material);
    for (std::size_t t = 0; t < corners.size(); t += 3) {
      const auto b = static_cast<std::uint32_t>(base);
      mesh_.indices.insert(mesh_.indices.end(), {b + corners[t], b + corners[t + 1], b + corners[t + 2]});
      mesh_.face_materials.push_back(local);
      mesh_.face_ids.push_back(face++);
    }
  }

  // The file's material in the mesh being read, added to its materials at first use.
  std::int32_t local_material(int material) {
    std::int32_t& local = local_materials_[static_cast<std::size_t>(material)];
    if (local < 0) {
      local = static_cast<std::int32_t>(mesh_.materials.size());
      mesh_.materials.push_back(materials_[static_cast<std::size_t>(material)]);
    }
    return local;
  }

  void append_normals(const std::vector<float>& n, std::size_t count) {
    if (n.empty()) {
      all_normals_ = false;
      mesh_.normals.resize(mesh_.positions.size(), glm::vec3(0, 0, 1));
      return;
    }
    for (std::size_t i = 0; i < count; ++i) {
      const glm::vec3 v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
      const float length = glm::length(v);
      mesh_.normals.push_back(std::isfinite(length) && length > 0.0f ? v / length : glm::vec3(0, 0, 1));
    }
  }

  // Unit xyz and a w of +1 or -1; a zero tangent where it has no direction, so that pixel's frame comes from its
  // derivatives instead. (A texture transform's rotation is not applied to them.)
  void append_tangents(const std::vector<float>& t, std::size_t count) {
    if (t.empty()) {
      mesh_.tangents.resize(mesh_.positions.size(), glm::vec4(0.0f));
      return;
    }
    any_tangents_ = true;
    for (std::size_t i = 0; i < count; ++i) {
      const glm::vec3 v(t[4 * i], t[4 * i + 1], t[4 * i + 2]);
      const float length = glm::length(v);
      mesh_.tangents.push_back(std::isfinite(length) && length > 0.0f
                                   ? glm::vec4(v / length, t[4 * i + 3] < 0.0f ? -1.0f : 1.0f)
                                   : glm::vec4(0.0f));
    }
  }

  // The material's texture transform is applied here, in glTF's texture space (origin at the image's top-left):
  // each primitive's vertices are its own in the mesh. Then v becomes 1 - v, facet's (and OpenGL's) bottom-left
  // origin, as OBJ, PLY and Assimp's readers give it, so a mesh's uvs mean the same whatever file it came from.
  void append_uvs(std::vector<glm::vec2>& into, bool& any, const std::vector<float>& uv, std::size_t count,
                  const glm::mat3& uv_transform) {
    if (uv.empty()) {
      into.resize(mesh_.positions.size(), glm::vec2(0.0f));
      return;
    }
    any = true;
    for (std::size_t i = 0; i < count; ++i) {
      const glm::vec3 moved = uv_transform * glm::vec3(uv[2 * i], uv[2 * i + 1], 1.0f);
      into.emplace_back(moved.x, 1.0f - moved.y);
    }
  }

  void append_colors(const std::vector<float>& c, int components, std::size_t count) {
    if (c.empty()) {
      mesh_.colors.resize(mesh_.positions.size(), glm::vec4(1.0f));
      return;
    }
    any_colors_ = true;
    const auto k = static_cast<std::size_t>(components);
    // COLOR_0 is linear; facet's vertex colours are as displayed (mesh.hpp).
    for (std::size_t i = 0; i < count; ++i)
      mesh_.colors.push_back(
          linear_to_srgb(glm::vec4(c[k * i], c[k * i + 1], c[k * i + 2], components == 4 ? c[k * i + 3] : 1.0f)));
  }

  const tinygltf::Model& model_;
  Reader reader_;
  DeformationReader deformation_;
  Model out_;
  std::vector<Material> materials_;       // the file's, decoded once
  std::vector<glm::mat3> uv_transforms_;  // per material: its base colour texture's KHR_texture_transform
  std::vector<std::uint32_t> slots_;      // per glTF mesh: its index in out_.meshes, kUnread or kNoTriangles
  std::set<int> on_path_;
  std::size_t expanded_ = 0;  // vertices of every instance placed so far
  // The mesh being read.
  Mesh mesh_;
  std::vector<std::int32_t> local_materials_;  // per file material: its index in mesh_.materials, or -1
  bool all_normals_ = true, any_uvs_ = false, any_uvs1_ = false, any_tangents_ = false, any_colors_ = false;
  bool warned_lines_ = false;
  std::set<int> warned_lights_;
};

}  // namespace

bool is_gltf_binary(std::string_view bytes) { return bytes.size() >= 12 && bytes.substr(0, 4) == "glTF"; }

namespace {

// What tinygltf's file and image callbacks need: where the model is, what it may read, and where to warn.
struct GltfAccess {
  ReferencePolicy policy;
  const LoadOptions* options = nullptr;
  std::string base;  // the folder as tinygltf joins names to it
  std::string source;
  std::set<std::string> noted;  // files already warned about: tinygltf may look a file up more than once
  std::string refused;          // the first file that could not be read, and why: a failed load's error
  // The model being loaded: tinygltf hands load_image an image's buffer view without checking that the view lies
  // inside its buffer, so load_image checks it against the buffers and views parsed before the images.
  const tinygltf::Model* model = nullptr;
};

// tinygltf joins a buffer's or image's URI to the model's folder; the part after the folder is the name the file
// wrote, found as the policy allows (references.hpp). "" (which does not exist) when nothing may be read.
std::string expand_path(const std::string& joined, void* user) {
  auto& access = *static_cast<GltfAccess*>(user);
  std::string name = joined;
  if (!access.base.empty()) {
    const std::string prefix = access.base.back() == '/' ? access.base : access.base + "/";
    if (name.starts_with(prefix)) name.erase(0, prefix.size());
  }
  const Reference found = resolve_reference(access.policy, name);
  if (!found.path) {
    if (access.refused.empty())
      access.refused = "'" + printable(name) + "': " +
                       (found.note.empty() ? printable(found.problem)
                                           : "outside the model's folder, and no '" +
                                                 printable(std::filesystem::path(name).filename().string()) +
                                                 "' beside it (" + setting("allow_external_files") + " reads it)");
    return {};
  }
  if (!found.note.empty() && access.noted.insert(found.note).second)
    warn(access.source, "'" + printable(name) + "' " + printable(found.note));
  return found.path->string();
}

bool file_exists(const std::string& path, void*) {
  std::error_code ec;
  return !path.empty() && std::filesystem::is_regular_file(path, ec);
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* error, const std::string& path, void*) {
  try {
    const FileBytes bytes = read_regular_file(path, kMaxModelFileBytes, path);
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputError& e) {
    if (error) *error += std::string(e.what()) + "\n";
    return false;
  }
}

bool refuse_write(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
  if (error) *error += "facet does not write glTF files\n";
  return false;
}

// The undecoded format of kUndecodedFormats an image file is in, from its signature; nullptr for any other.
const UndecodedFormat* undecoded_format(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kKtx2[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  if (bytes.size() >= 12 && std::equal(kKtx2, kKtx2 + 12, bytes.begin())) return &kUndecodedFormats[0];
  if (bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0)
    return &kUndecodedFormats[1];
  return nullptr;
}

// Images are decoded by facet's decoders (image_decode.hpp), not tinygltf's stb_image. One that cannot be
// decoded, or is larger than the limit (a small PNG can expand to gigabytes), leaves its material untextured with
// a warning; its width is set to kWarnedImage so that decode_texture knows the warning was given. KTX2 and WebP
// images are left for decode_texture to name (kUndecodedImage), with no warning here.
bool load_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto& access = *static_cast<GltfAccess*>(user);
  if (image->bufferView >= 0) {
    const auto& views = access.model->bufferViews;
    const auto& buffers = access.model->buffers;
    const auto view = static_cast<std::size_t>(image->bufferView);
    const bool inside = view < views.size() && views[view].buffer >= 0 &&
                        static_cast<std::size_t>(views[view].buffer) < buffers.size() &&
                        views[view].byteOffset <= buffers[static_cast<std::size_t>(views[view].buffer)].data.size() &&
                        views[view].byteLength <=
                            buffers[static_cast<std::size_t>(views[view].buffer)].data.size() - views[view].byteOffset;
    if (!inside) {
      if (access.refused.empty())
        access.refused = "image " + std::to_string(index) + ": buffer view " + std::to_string(view) +
                         " reaches past the end of its buffer";
      return false;
    }
  }
  const std::span<const unsigned char> file(bytes, static_cast<std::size_t>(std::max(size, 0)));
  if (const UndecodedFormat* format = undecoded_format(file)) {
    image->width = kUndecodedImage;
    image->mimeType = format->mime_type;
    return true;
  }
  try {
    DecodedImage decoded = decode_image(file, access.options->max_texture_size, "image " + std::to_string(index));
    image->width = decoded.width;
    image->height = decoded.height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(decoded.rgba);
  } catch (const InputError& e) {
    warn(access.source, std::string(e.what()) + " (" + setting("max_texture_size") +
                            " sets the size limit); drawing its material untextured");
    image->width = kWarnedImage;
  }
  return true;
}

}  // namespace

Model load_gltf(const std::filesystem::path& path, std::string_view bytes, const std::string& source,
                const LoadOptions& options) {
  tinygltf::TinyGLTF gltf;
  tinygltf::Model model;
  std::string error, warning;
  const std::string base = path.parent_path().string();
  GltfAccess access{{path.parent_path(), options.allow_external_files}, &options, base, source, {}, {}};
  gltf.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &refuse_write, &access});
  access.model = &model;
  gltf.SetImageLoader(&load_image, &access);
  if (is_gltf_binary(bytes) && bytes.size() >= 12) {
    std::uint32_t stated = 0;
    std::memcpy(&stated, bytes.data() + 8, 4);
    if (stated > bytes.size())
      throw InputError(source, "the GLB header gives its length as " + std::to_string(stated) +
                                   " bytes, but the file has only " + std::to_string(bytes.size()) +
                                   ": it is cut short");
  }
  // Rewritten for tinygltf, which cannot read some files that use Draco or meshoptimizer as they are
  // (gltf_primitive.hpp, gltf_meshopt.hpp).
  const std::optional<std::string> patched = without_draco_indices(bytes, is_gltf_binary(bytes));
  if (patched) bytes = *patched;
  const std::optional<std::string> repatched = without_meshopt_placeholders(bytes, is_gltf_binary(bytes));
  if (repatched) bytes = *repatched;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const bool ok =
      is_gltf_binary(bytes)
          ? gltf.LoadBinaryFromMemory(&model, &error, &warning, data, static_cast<unsigned>(bytes.size()), base)
          : gltf.LoadASCIIFromString(&model, &error, &warning, bytes.data(), static_cast<unsigned>(bytes.size()), base);
  const auto first_line = [](std::string text) {
    text = text.substr(0, text.find('\n'));
    return printable(text.empty() ? "not a valid glTF file" : text);
  };
  if (!ok) throw InputError(source, access.refused.empty() ? first_line(error) : access.refused);
  if (!warning.empty()) warn(source, first_line(warning));
  for (const std::string& extension : model.extensionsRequired) {
    if (kSupportedRequired.count(extension)) continue;
    if (extension == "EXT_meshopt_compression")
      throw InputError(source, "this build cannot decode EXT_meshopt_compression, which the file requires");
    throw InputError(source, "requires the glTF extension " + printable(extension) + ", which facet does not support");
  }
  // Compressed buffer views are decoded before any accessor is read.
  decode_meshopt(model, source);

  SceneReader scene_reader(model, source);
  const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (static_cast<std::size_t>(scene) < model.scenes.size()) {
    for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes) scene_reader.node(root, glm::mat4(1.0f), 0);
  } else {
    // No scenes: every node that is nobody's child is a root.
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const tinygltf::Node& n : model.nodes)
      for (int child : n.children)
        if (child >= 0 && static_cast<std::size_t>(child) < is_child.size())
          is_child[static_cast<std::size_t>(child)] = true;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) scene_reader.node(static_cast<int>(i), glm::mat4(1.0f), 0);
  }
  return scene_reader.finish();
}

}  // namespace facet
