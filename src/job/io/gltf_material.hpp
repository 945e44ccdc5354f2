// gltf_material.hpp - a glTF file's materials as facet's Material: factors, textures, samplers, texture transforms.
#pragma once

#include <tiny_gltf.h>

#include <memory>
#include <set>
#include <string>

#include <glm/glm.hpp>

#include "facet/mesh.hpp"
#include "facet/texture.hpp"

namespace facet {

// Texture extensions whose images facet cannot decode: KTX2 (Basis Universal) and WebP. load_image leaves such
// images undecoded without a word (a texture may offer a PNG or JPEG image beside them), marking them with
// kUndecodedImage and their MIME type; decode_texture names the extension when a material needs one.
struct UndecodedFormat {
  const char* extension;
  const char* format;
  const char* mime_type;
};
inline constexpr UndecodedFormat kUndecodedFormats[] = {{"KHR_texture_basisu", "KTX2", "image/ktx2"},
                                                        {"EXT_texture_webp", "WebP", "image/webp"}};
// Image widths load_image leaves instead of decoding: a warning given, or a format above.
inline constexpr int kWarnedImage = -1, kUndecodedImage = -2;

// KHR_texture_transform of a texture reference as one matrix on (u, v, 1): translation * rotation * scale, in the
// extension's order and with its rotation sense. Identity without the extension.
glm::mat3 uv_transform_of(const tinygltf::TextureInfo& info, const std::string& source);

// The material a glTF material describes (mesh.hpp: colours as displayed, linear factors encoded), its textures
// decoded; `warned_textures` holds the textures already warned about, so each is named once.
Material material_of(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& source,
                     std::set<int>& warned_textures);

// The material the specification gives a primitive without one: white, fully metallic, fully rough, one-sided.
Material default_material();

}  // namespace facet
