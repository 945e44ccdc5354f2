// gltf_draco.cpp - glTF's KHR_draco_mesh_compression: a primitive's compressed buffer view decoded with Draco.
#include <tiny_gltf.h>

// A build without Draco (the browser page's, FACET_NO_DRACO) refuses compressed primitives with that reason.
#ifndef FACET_NO_DRACO
#include <draco/compression/decode.h>
#endif
#include <nlohmann/json.hpp>

#include <cstring>
#include <string>
#include <string_view>

#include "facet/error.hpp"
#include "job/io/gltf_primitive.hpp"

namespace facet {
namespace {

int integer_member(const tinygltf::Value& object, const char* key) {
  if (!object.Has(key) || !object.Get(key).IsInt()) return -1;
  return object.Get(key).GetNumberAsInt();
}

// The JSON with "indices" removed from every Draco-compressed primitive; nullopt when there is none (or the text
// does not parse: tinygltf then reports the problem).
std::optional<std::string> json_without_draco_indices(std::string_view json, bool) {
  if (json.find("KHR_draco_mesh_compression") == std::string_view::npos) return std::nullopt;
  nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
  if (document.is_discarded() || !document.is_object() || !document.contains("meshes")) return std::nullopt;
  bool changed = false;
  for (nlohmann::json& mesh : document["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives")) continue;
    for (nlohmann::json& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("extensions")) continue;
      const nlohmann::json& extensions = primitive["extensions"];
      if (extensions.is_object() && extensions.contains("KHR_draco_mesh_compression"))
        changed = primitive.erase("indices") > 0 || changed;
    }
  }
  if (!changed) return std::nullopt;
  return document.dump();
}

std::uint32_t load_u32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

}  // namespace

std::optional<std::string> with_gltf_json_rewritten(std::string_view bytes, bool binary, JsonRewrite rewrite) {
  if (!binary) return rewrite(bytes, false);
  // GLB: a 12-byte header, then the JSON chunk (length, "JSON", text) and any others after it.
  if (bytes.size() < 20 || load_u32(bytes.data() + 16) != 0x4E4F534Au) return std::nullopt;
  const std::uint32_t length = load_u32(bytes.data() + 12);
  if (length > bytes.size() - 20) return std::nullopt;
  // Only a file whose header and chunks agree with its size is rewritten: the rewrite states the new size, which
  // would hide from tinygltf a file that lies about it (and a chunk that reaches past its end).
  if (load_u32(bytes.data() + 8) != bytes.size()) return std::nullopt;  // (load_gltf refuses a longer one)
  for (std::size_t at = 20 + std::size_t{length}; at < bytes.size();) {
    if (bytes.size() - at < 8) return std::nullopt;
    const std::uint32_t chunk = load_u32(bytes.data() + at);
    if (chunk > bytes.size() - at - 8) return std::nullopt;
    at += 8 + std::size_t{chunk};
  }
  std::optional<std::string> json = rewrite(bytes.substr(20, length), true);
  if (!json) return std::nullopt;
  json->append((4 - json->size() % 4) % 4, ' ');  // chunks stay 4-byte aligned
  const auto new_length = static_cast<std::uint32_t>(json->size());
  std::string out(bytes.substr(0, 12));
  out.append(reinterpret_cast<const char*>(&new_length), 4);
  out.append("JSON", 4);
  out += *json;
  out.append(bytes.substr(20 + length));
  const auto total = static_cast<std::uint32_t>(out.size());
  std::memcpy(out.data() + 8, &total, 4);
  return out;
}

std::optional<std::string> without_draco_indices(std::string_view bytes, bool binary) {
  return with_gltf_json_rewritten(bytes, binary, &json_without_draco_indices);
}

PrimitiveArrays decode_draco(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                             std::size_t max_vertices, const std::string& source) {
  const auto fail = [&](const std::string& problem) { throw InputError(source, "Draco-compressed mesh: " + problem); };
  const tinygltf::Value& extension = primitive.extensions.at("KHR_draco_mesh_compression");
  const int view_index = integer_member(extension, "bufferView");
  if (view_index < 0 || static_cast<std::size_t>(view_index) >= model.bufferViews.size())
    fail("buffer view " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    fail("buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)
    fail("buffer view " + std::to_string(view_index) + " reaches past the end of its buffer");

#ifdef FACET_NO_DRACO
  fail("this build of facet has no Draco decoder (" + std::to_string(max_vertices) + " vertices allowed)");
  return {};
#else
  draco::DecoderBuffer data;
  data.Init(reinterpret_cast<const char*>(buffer.data() + view.byteOffset), view.byteLength);
  const auto type = draco::Decoder::GetEncodedGeometryType(&data);
  if (!type.ok() || type.value() != draco::TRIANGULAR_MESH) fail("not a Draco triangle mesh");
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&data);
  if (!decoded.ok()) fail("Draco cannot decode it (" + decoded.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const std::size_t points = mesh->num_points();
  if (points > max_vertices) fail("more than " + std::to_string(max_vertices) + " vertices");

  PrimitiveArrays out;
  const tinygltf::Value attributes = extension.Get("attributes");
  // Each attribute the extension maps, as floats: `components` per point, or any count in `allowed` (colours).
  const auto read = [&](const char* name, std::vector<float>& values, int components, int allowed = 0) {
    const int id = attributes.IsObject() ? integer_member(attributes, name) : -1;
    if (id < 0) return 0;
    const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
    if (!attribute) fail(std::string(name) + " is attribute " + std::to_string(id) + ", which the data does not hold");
    const int held = attribute->num_components();
    if (held != components && held != allowed)
      fail(std::string(name) + " has " + std::to_string(held) + " components, not " + std::to_string(components));
    values.resize(points * static_cast<std::size_t>(held));
    for (std::size_t i = 0; i < points; ++i) {
      const draco::AttributeValueIndex value =
          attribute->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
      if (!attribute->ConvertValue<float>(value, static_cast<std::int8_t>(held), &values[i * held]))
        fail(std::string(name) + " cannot be read as numbers");
    }
    return held;
  };
  if (read("POSITION", out.positions, 3) == 0) fail("it has no POSITION attribute");
  read("NORMAL", out.normals, 3);
  read("TEXCOORD_0", out.uvs, 2);
  const int color_components = read("COLOR_0", out.colors, 4, 3);
  if (color_components != 0) out.color_components = color_components;

  out.indexed = true;
  out.corners.reserve(3 * static_cast<std::size_t>(mesh->num_faces()));
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out.corners.push_back(mesh->face(f)[k].value());
  return out;
#endif
}

}  // namespace facet
