// gltf_material.cpp - a glTF file's materials as facet's Material: factors, textures, samplers, texture transforms,
// and the extensions that refine them (emissive strength, unlit, ior, specular, clearcoat, sheen, transmission).
#include "job/io/gltf_material.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "facet/color.hpp"
#include "facet/error.hpp"
#include "job/io/loaders.hpp"

namespace facet {

namespace {

// glTF images are stored top row first with v = 0 at the top, so rows are kept in file order. A texture with only a
// KTX2 or WebP image is warned about once (`warned` holds the textures warned about), naming its extension.
std::shared_ptr<const Texture> decode_texture(const tinygltf::Model& model, int texture_index, TexelEncoding encoding,
                                              const std::string& source, std::set<int>& warned) {
  if (texture_index < 0 || static_cast<std::size_t>(texture_index) >= model.textures.size()) return nullptr;
  const tinygltf::Texture& texture = model.textures[static_cast<std::size_t>(texture_index)];
  const auto undecoded = [&](const std::string& problem) -> std::shared_ptr<const Texture> {
    if (warned.insert(texture_index).second)
      warn(source, "texture " + std::to_string(texture_index) + " " + problem +
                       ", which facet cannot decode; drawing its material untextured");
    return nullptr;
  };
  const int image_index = texture.source;
  if (image_index < 0 || static_cast<std::size_t>(image_index) >= model.images.size()) {
    for (const UndecodedFormat& f : kUndecodedFormats)
      if (texture.extensions.count(f.extension))
        return undecoded(std::string("has only a ") + f.format + " image (" + f.extension + ")");
    return nullptr;
  }
  const tinygltf::Image& image = model.images[static_cast<std::size_t>(image_index)];
  if (image.width == kUndecodedImage)
    for (const UndecodedFormat& f : kUndecodedFormats)
      if (image.mimeType == f.mime_type)
        return undecoded("has a " + std::string(f.format) + " image (" + f.extension + "), image " +
                         std::to_string(image_index));
  if (image.width == kWarnedImage) return nullptr;  // too large or unreadable: load_image has warned
  const std::size_t texels = static_cast<std::size_t>(std::max(image.width, 0)) * std::max(image.height, 0);
  if (texels == 0 || image.bits != 8 || image.component < 1 || image.component > 4 ||
      image.image.size() != texels * static_cast<std::size_t>(image.component)) {
    warn(source, "image " + std::to_string(image_index) + " (" + printable(image.uri) +
                     ") could not be decoded; drawing its material untextured");
    return nullptr;
  }
  // Rows flipped, as load_texture flips image files: texture row 0 is v = 0, the image's bottom row (OpenGL's
  // convention, which append_uvs turns glTF's top-left texture coordinates into).
  std::vector<std::uint32_t> rgba(texels);
  const int n = image.component;
  const auto width = static_cast<std::size_t>(image.width), height = static_cast<std::size_t>(image.height);
  for (std::size_t i = 0; i < texels; ++i) {
    const unsigned char* p = image.image.data() + i * static_cast<std::size_t>(n);
    const std::uint32_t r = p[0], g = n >= 3 ? p[1] : p[0], b = n >= 3 ? p[2] : p[0];
    const std::uint32_t a = n == 4 ? p[3] : n == 2 ? p[1] : 255;
    rgba[(height - 1 - i / width) * width + i % width] = r | g << 8 | b << 16 | a << 24;
  }
  try {
    auto texture = std::make_shared<Texture>(image.width, image.height, std::move(rgba), encoding);
    texture->generate_mipmaps();
    return texture;
  } catch (const std::invalid_argument& e) {
    warn(source, "image " + std::to_string(image_index) + ": " + e.what() + "; drawing its material untextured");
    return nullptr;
  }
}

// The texture's filtering and wrapping from its glTF sampler (OpenGL enums); unset when it has none, which glTF
// defines as repeat with filtering left to the renderer. One Filter stands for both of glTF's: mipmapped
// minification means trilinear, NEAREST for both means nearest, anything else bilinear.
std::optional<Sampler> sampler_of(const tinygltf::Model& model, int texture_index) {
  if (texture_index < 0 || static_cast<std::size_t>(texture_index) >= model.textures.size()) return std::nullopt;
  const int index = model.textures[static_cast<std::size_t>(texture_index)].sampler;
  if (index < 0 || static_cast<std::size_t>(index) >= model.samplers.size()) return std::nullopt;
  const tinygltf::Sampler& gl = model.samplers[static_cast<std::size_t>(index)];
  const auto wrap = [](int mode) {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::clamp;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::mirror;
      default: return Wrap::repeat;
    }
  };
  Sampler out;
  out.wrap_u = wrap(gl.wrapS);
  out.wrap_v = wrap(gl.wrapT);
  const bool mipmapped = gl.minFilter >= TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST &&
                         gl.minFilter <= TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  if (mipmapped || (gl.minFilter < 0 && gl.magFilter < 0)) out.filter = Filter::trilinear;
  else if (gl.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST && gl.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR)
    out.filter = Filter::nearest;
  else out.filter = Filter::bilinear;
  return out;
}

// A factor clamped to [0, 1] as the specification bounds it; NaN gives the default.
float unit_factor(double value, float fallback) {
  return std::isfinite(value) ? static_cast<float>(std::clamp(value, 0.0, 1.0)) : fallback;
}
template <int N>
glm::vec<N, float> unit_vector(const std::vector<double>& values) {
  glm::vec<N, float> out(1.0f);
  for (int i = 0; i < N; ++i) out[i] = unit_factor(values[static_cast<std::size_t>(i)], 1.0f);
  return out;
}

// The texture index of a textureInfo inside an extension's JSON; -1 when absent or malformed.
int texture_index_of(const tinygltf::Value& extension, const char* key) {
  if (!extension.Has(key) || !extension.Get(key).IsObject()) return -1;
  const tinygltf::Value& index = extension.Get(key).Get("index");
  return index.IsInt() ? index.GetNumberAsInt() : -1;
}

// The uv set a textureInfo inside an extension's JSON reads (its texCoord; 0 when absent).
int texcoord_of(const tinygltf::Value& extension, const char* key) {
  if (!extension.Has(key) || !extension.Get(key).IsObject()) return 0;
  const tinygltf::Value& set = extension.Get(key).Get("texCoord");
  return set.IsInt() ? set.GetNumberAsInt() : 0;
}

// Marks `slot` in out.uv1_maps when its texture reads TEXCOORD_1; another set than 0 or 1 is read as 0, with a
// warning.
void read_uv_set(int texcoord, std::uint32_t slot, Material& out, const std::string& source) {
  if (texcoord == 1) out.uv1_maps |= slot;
  else if (texcoord != 0)
    warn(source, "material '" + printable(out.name) + "': a texture reads TEXCOORD_" + std::to_string(texcoord) +
                     ", which facet does not read; using TEXCOORD_0");
}

// A number of an extension's JSON, or nullopt when it is absent; a present non-number gives NaN, so that the
// caller's range check warns about it.
std::optional<double> number_of(const tinygltf::Value& extension, const char* key) {
  if (!extension.Has(key)) return std::nullopt;
  const tinygltf::Value& v = extension.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
}

// KHR_materials_ior and KHR_materials_specular into `out`. Values the specification does not allow are warned
// about and replaced by its defaults, so a malformed file still draws as the core material would.
template <class DecodeTexture>
void read_dielectric_extensions(const tinygltf::Material& m, const std::string& source, Material& out,
                                const DecodeTexture& texture) {
  const std::string material = "material '" + printable(m.name) + "': ";
  if (const auto e = m.extensions.find("KHR_materials_ior"); e != m.extensions.end() && e->second.IsObject()) {
    if (const std::optional<double> ior = number_of(e->second, "ior")) {
      // 0 is allowed (the specular-glossiness mode); otherwise an index of refraction is at least that of vacuum.
      if (*ior == 0.0 || (std::isfinite(*ior) && *ior >= 1.0)) out.ior = static_cast<float>(*ior);
      else warn(source, material + "KHR_materials_ior's ior must be 0 or a finite number of at least 1; using 1.5");
    }
  }
  const auto e = m.extensions.find("KHR_materials_specular");
  if (e == m.extensions.end() || !e->second.IsObject()) return;
  const tinygltf::Value& specular = e->second;
  if (const std::optional<double> factor = number_of(specular, "specularFactor")) {
    // Above 1 is clamped as the other unit factors are; negative or not a number is an error.
    if (std::isfinite(*factor) && *factor >= 0.0) out.specular_factor = unit_factor(*factor, 1.0f);
    else warn(source, material + "specularFactor must be a finite number in [0, 1]; using 1");
  }
  if (specular.Has("specularColorFactor")) {
    const tinygltf::Value& c = specular.Get("specularColorFactor");
    glm::vec3 color(1.0f);
    bool valid = c.IsArray() && c.ArrayLen() == 3;
    for (int i = 0; valid && i < 3; ++i) {
      const double v = c.Get(i).IsNumber() ? c.Get(i).GetNumberAsDouble() : -1.0;
      valid = std::isfinite(v) && v >= 0.0 && v <= std::numeric_limits<float>::max();
      color[i] = static_cast<float>(v);
    }
    if (valid) out.specular_color_factor = color;
    else warn(source, material + "specularColorFactor must be three finite numbers of at least 0; using 1, 1, 1");
  }
  out.specular_map = texture(texture_index_of(specular, "specularTexture"), TexelEncoding::linear);
  out.specular_color_map = texture(texture_index_of(specular, "specularColorTexture"), TexelEncoding::srgb);
  if (out.specular_map) read_uv_set(texcoord_of(specular, "specularTexture"), texture_slot::specular, out, source);
  if (out.specular_color_map)
    read_uv_set(texcoord_of(specular, "specularColorTexture"), texture_slot::specular_color, out, source);
}

// An extension object of a material, or nullptr.
const tinygltf::Value* extension_of(const tinygltf::Material& m, const char* name) {
  const auto e = m.extensions.find(name);
  return e != m.extensions.end() && e->second.IsObject() ? &e->second : nullptr;
}

// KHR_materials_clearcoat and KHR_materials_sheen into `out`. Factors outside [0, 1] are clamped and anything that
// is not a number is replaced by the default, with a warning naming the material and the key.
template <class DecodeTexture>
void read_layer_extensions(const tinygltf::Material& m, const std::string& source, Material& out,
                           const DecodeTexture& texture) {
  const std::string material = "material '" + printable(m.name) + "': ";
  const auto unit = [&](const tinygltf::Value& e, const char* key, float fallback) {
    const std::optional<double> v = number_of(e, key);
    if (!v) return fallback;
    if (*v >= 0.0 && *v <= 1.0) return static_cast<float>(*v);
    warn(source, material + key + " must be a number in [0, 1]; " +
                     (std::isfinite(*v) ? "clamping it" : "using its default"));
    return unit_factor(*v, fallback);
  };
  if (const tinygltf::Value* coat = extension_of(m, "KHR_materials_clearcoat")) {
    out.clearcoat = unit(*coat, "clearcoatFactor", 0.0f);
    out.clearcoat_map = texture(texture_index_of(*coat, "clearcoatTexture"), TexelEncoding::linear);
    out.clearcoat_roughness = unit(*coat, "clearcoatRoughnessFactor", 0.0f);
    out.clearcoat_roughness_map = texture(texture_index_of(*coat, "clearcoatRoughnessTexture"), TexelEncoding::linear);
    out.clearcoat_normal_map = texture(texture_index_of(*coat, "clearcoatNormalTexture"), TexelEncoding::linear);
    read_uv_set(texcoord_of(*coat, "clearcoatTexture"), texture_slot::clearcoat, out, source);
    read_uv_set(texcoord_of(*coat, "clearcoatRoughnessTexture"), texture_slot::clearcoat_roughness, out, source);
    read_uv_set(texcoord_of(*coat, "clearcoatNormalTexture"), texture_slot::clearcoat_normal, out, source);
    if (out.clearcoat_normal_map) {
      const std::optional<double> scale = number_of(coat->Get("clearcoatNormalTexture"), "scale");
      if (scale && std::isfinite(*scale)) out.clearcoat_normal_scale = static_cast<float>(*scale);
    }
  }
  if (const tinygltf::Value* sheen = extension_of(m, "KHR_materials_sheen")) {
    if (sheen->Has("sheenColorFactor")) {
      const tinygltf::Value& c = sheen->Get("sheenColorFactor");
      glm::vec3 color(0.0f);
      bool valid = c.IsArray() && c.ArrayLen() == 3;
      for (int i = 0; valid && i < 3; ++i) {
        const double v = c.Get(i).IsNumber() ? c.Get(i).GetNumberAsDouble() : std::nan("");
        valid = v >= 0.0 && v <= 1.0;  // false for NaN
        color[i] = static_cast<float>(v);
      }
      if (valid) out.sheen_color = color;
      else warn(source, material + "sheenColorFactor must be three numbers in [0, 1]; using black (no sheen)");
    }
    out.sheen_color_map = texture(texture_index_of(*sheen, "sheenColorTexture"), TexelEncoding::srgb);
    out.sheen_roughness = unit(*sheen, "sheenRoughnessFactor", 0.0f);
    out.sheen_roughness_map = texture(texture_index_of(*sheen, "sheenRoughnessTexture"), TexelEncoding::linear);
    read_uv_set(texcoord_of(*sheen, "sheenColorTexture"), texture_slot::sheen_color, out, source);
    read_uv_set(texcoord_of(*sheen, "sheenRoughnessTexture"), texture_slot::sheen_roughness, out, source);
  }
  if (const tinygltf::Value* transmission = extension_of(m, "KHR_materials_transmission")) {
    out.transmission = unit(*transmission, "transmissionFactor", 0.0f);
    out.transmission_map = texture(texture_index_of(*transmission, "transmissionTexture"), TexelEncoding::linear);
    read_uv_set(texcoord_of(*transmission, "transmissionTexture"), texture_slot::transmission, out, source);
  }
}

}  // namespace

// KHR_texture_transform of a texture reference as one matrix on (u, v, 1): translation * rotation * scale, in the
// extension's order and with its rotation sense. Identity without the extension.
glm::mat3 uv_transform_of(const tinygltf::TextureInfo& info, const std::string& source) {
  const auto found = info.extensions.find("KHR_texture_transform");
  if (found == info.extensions.end() || !found->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& t = found->second;
  const auto number = [](const tinygltf::Value& v, double fallback) {
    const double x = v.IsNumber() ? v.GetNumberAsDouble() : fallback;
    return std::isfinite(x) ? static_cast<float>(x) : static_cast<float>(fallback);
  };
  const auto pair = [&](const char* key, float fallback) {
    if (!t.Has(key) || !t.Get(key).IsArray() || t.Get(key).ArrayLen() != 2) return glm::vec2(fallback);
    return glm::vec2(number(t.Get(key).Get(0), fallback), number(t.Get(key).Get(1), fallback));
  };
  if (t.Has("texCoord") && number(t.Get("texCoord"), 0.0) != 0.0f)
    warn(source, "KHR_texture_transform's texCoord is not read; the texture keeps its own coordinate set");
  const glm::vec2 offset = pair("offset", 0.0f), scale = pair("scale", 1.0f);
  const float rotation = t.Has("rotation") ? number(t.Get("rotation"), 0.0) : 0.0f;
  const float c = std::cos(rotation), s = std::sin(rotation);
  // Columns: glm is column-major. [1 0 ox; 0 1 oy] * [c s; -s c] * [sx 0; 0 sy].
  return glm::mat3(glm::vec3(c * scale.x, -s * scale.x, 0.0f), glm::vec3(s * scale.y, c * scale.y, 0.0f),
                   glm::vec3(offset, 1.0f));
}

// The material the specification gives a primitive without one: white, fully metallic, fully rough, one-sided.
Material default_material() {
  Material out;
  out.name = "glTF default";
  out.metallic = 1.0f;
  out.roughness = 1.0f;
  out.double_sided = false;
  return out;
}

Material material_of(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& source,
                     std::set<int>& warned_textures) {
  const auto texture = [&](int index, TexelEncoding encoding) {
    return decode_texture(model, index, encoding, source, warned_textures);
  };
  Material out;
  out.name = m.name;
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  // glTF's factors are linear; facet's material colours are as displayed (mesh.hpp).
  if (pbr.baseColorFactor.size() == 4) out.diffuse = linear_to_srgb(unit_vector<4>(pbr.baseColorFactor));
  out.metallic = unit_factor(pbr.metallicFactor, 1.0f);
  out.roughness = unit_factor(pbr.roughnessFactor, 1.0f);
  // For the Blinn-Phong and Phong shadings: rough surfaces get a weak, broad highlight.
  out.specular = glm::vec3(0.5f * (1.0f - out.roughness));
  out.shininess = 2.0f + 126.0f * (1.0f - out.roughness) * (1.0f - out.roughness);
  out.diffuse_map = texture(pbr.baseColorTexture.index, TexelEncoding::srgb);
  out.sampler = sampler_of(model, pbr.baseColorTexture.index);
  out.metallic_roughness_map = texture(pbr.metallicRoughnessTexture.index, TexelEncoding::linear);
  out.normal_map = texture(m.normalTexture.index, TexelEncoding::linear);
  out.normal_scale = std::isfinite(m.normalTexture.scale) ? static_cast<float>(m.normalTexture.scale) : 1.0f;
  out.occlusion_map = texture(m.occlusionTexture.index, TexelEncoding::linear);
  out.occlusion_strength = unit_factor(m.occlusionTexture.strength, 1.0f);
  if (m.emissiveFactor.size() == 3) {
    float strength = 1.0f;
    if (const auto e = m.extensions.find("KHR_materials_emissive_strength");
        e != m.extensions.end() && e->second.Has("emissiveStrength")) {
      const double value = e->second.Get("emissiveStrength").GetNumberAsDouble();
      if (std::isfinite(value) && value >= 0.0) strength = static_cast<float>(value);
      else warn(source, "material '" + m.name + "': emissiveStrength must be finite and not negative; using 1");
    }
    out.emissive = glm::vec3(unit_vector<3>(m.emissiveFactor)) * strength;
  }
  out.emissive_map = texture(m.emissiveTexture.index, TexelEncoding::srgb);
  namespace slot = texture_slot;
  if (out.diffuse_map) read_uv_set(pbr.baseColorTexture.texCoord, slot::base_color, out, source);
  if (out.metallic_roughness_map)
    read_uv_set(pbr.metallicRoughnessTexture.texCoord, slot::metallic_roughness, out, source);
  if (out.normal_map) read_uv_set(m.normalTexture.texCoord, slot::normal, out, source);
  if (out.occlusion_map) read_uv_set(m.occlusionTexture.texCoord, slot::occlusion, out, source);
  if (out.emissive_map) read_uv_set(m.emissiveTexture.texCoord, slot::emissive, out, source);
  out.unlit = m.extensions.count("KHR_materials_unlit") > 0;
  read_dielectric_extensions(m, source, out, texture);
  read_layer_extensions(m, source, out, texture);
  out.double_sided = m.doubleSided;
  if (m.alphaMode == "BLEND") out.alpha_mode = AlphaMode::blend;
  if (m.alphaMode == "MASK") {
    out.alpha_mode = AlphaMode::mask;
    if (std::isfinite(m.alphaCutoff)) out.alpha_cutoff = static_cast<float>(m.alphaCutoff);
  }
  // Transmission is drawn by blending what lies behind (pbr.hpp); a masked surface keeps its cut-out instead.
  if (out.transmission > 0.0f && out.alpha_mode == AlphaMode::opaque) out.alpha_mode = AlphaMode::blend;
  return out;
}

}  // namespace facet
