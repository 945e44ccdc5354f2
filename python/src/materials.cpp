// materials.cpp - the Python module's materials and textures: pyrender's MetallicRoughnessMaterial as a facet one.
#include "materials.hpp"

#include <cmath>
#include <utility>
#include <vector>

#include "facet/color.hpp"
#include "facet/model_io.hpp"

namespace facet::python {

// Texture images come top row first, as image files and numpy images do; texture row 0 is v = 0, the bottom.
std::shared_ptr<const Texture> texture_of(py::handle image, const std::string& name, TexelEncoding encoding) {
  const py::array a = py::array::ensure(image);
  if (!a) value_error(name + ": expected an image array");
  const bool bytes = a.dtype().kind() == 'u' && a.dtype().itemsize() == 1;
  const int dims = static_cast<int>(a.ndim());
  if (dims != 2 && dims != 3) value_error(name + ": expected H x W, H x W x 3 or H x W x 4");
  const auto f = checked_array<float>(a, name, "fiu", dims, {});
  const py::ssize_t h = f.shape(0), w = f.shape(1), c = dims == 3 ? f.shape(2) : 1;
  if (c != 1 && c != 3 && c != 4) value_error(name + ": expected 1, 3 or 4 channels, got " + std::to_string(c));
  if (h < 1 || w < 1 || h > kMaxTextureSize || w > kMaxTextureSize)
    value_error(name + ": " + std::to_string(w) + "x" + std::to_string(h) + " is outside 1.." +
                std::to_string(kMaxTextureSize) + " per side");
  const float scale = bytes ? 1.0f : 255.0f;
  const float* v = f.data();
  std::vector<std::uint32_t> texels(static_cast<std::size_t>(w * h));
  for (py::ssize_t y = 0; y < h; ++y)
    for (py::ssize_t x = 0; x < w; ++x) {
      const float* p = v + (y * w + x) * c;
      std::uint32_t rgba[4] = {0, 0, 0, 255};
      for (py::ssize_t k = 0; k < 4; ++k) {
        const float value = k < 3 ? p[c >= 3 ? k : 0] : (c == 4 ? p[3] : (bytes ? 255.0f : 1.0f));
        if (!(value >= 0.0f && value * scale <= 255.5f))
          value_error(name + (bytes ? ": bad value" : ": float values must lie in 0..1"));
        rgba[k] = static_cast<std::uint32_t>(value * scale + 0.5f);
      }
      texels[static_cast<std::size_t>((h - 1 - y) * w + x)] = rgba[0] | rgba[1] << 8 | rgba[2] << 16 | rgba[3] << 24;
    }
  auto texture = std::make_shared<Texture>(static_cast<int>(w), static_cast<int>(h), std::move(texels), encoding);
  texture->generate_mipmaps();
  return texture;
}

Material default_material() {
  Material out;
  out.name = "default";
  out.specular = glm::vec3(0.4f);
  out.shininess = 32.0f;
  out.double_sided = false;
  return out;
}

namespace {

// A number of the description within [lo, hi]; the Python class checked it already, so this guards the module
// against a hand-made dict only.
float factor(const py::dict& d, const char* key, float lo, float hi) {
  const float v = d[key].cast<float>();
  if (!(v >= lo && v <= hi))
    value_error(std::string("material: ") + key + " must lie in " + std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

template <int C>
glm::vec<C, float> vector_of(const py::dict& d, const char* key) {
  return finite_rows<C>(py::array::ensure(d[key]).reshape({1, C}), std::string("material: ") + key)[0];
}

}  // namespace

Material material_of(py::handle description, bool has_uvs) {
  const auto d = description.cast<py::dict>();
  Material out;
  out.name = d["name"].cast<std::string>();
  // Whose conventions the values follow: facet's own (Mesh.from_arrays), pyrender's lit shader, or pyrender's flat
  // shader, which writes base colour x texture x vertex colour unconverted.
  const std::string convention = d.contains("convention") ? d["convention"].cast<std::string>() : "facet";
  if (convention != "facet" && convention != "pyrender" && convention != "pyrender_flat")
    value_error("material: unknown convention '" + convention + "'");
  // pyrender's factors are linear, as glTF's are; Material holds the base colour as displayed (mesh.hpp).
  const glm::vec4 base = glm::clamp(vector_of<4>(d, "base_color"), 0.0f, 1.0f);
  out.diffuse = convention == "pyrender_flat" ? base : linear_to_srgb(base);
  out.metallic = factor(d, "metallic", 0.0f, 1.0f);
  out.roughness = factor(d, "roughness", 0.0f, 1.0f);
  // For the classic shadings, as the glTF reader derives them: rough surfaces get a weak, broad highlight.
  out.specular = glm::vec3(0.5f * (1.0f - out.roughness));
  out.shininess = 2.0f + 126.0f * (1.0f - out.roughness) * (1.0f - out.roughness);
  // Emission is linear radiance in Material as in pyrender: no encoding.
  out.emissive = glm::max(vector_of<3>(d, "emissive"), glm::vec3(0.0f));
  out.pyrender_lighting = convention == "pyrender";
  // pyrender's shader multiplies the emission (the factor times the texture) by the factor again.
  if (out.pyrender_lighting) out.emissive *= out.emissive;
  const std::string mode = d["alpha_mode"].cast<std::string>();
  if (mode == "BLEND") out.alpha_mode = AlphaMode::blend;
  else if (mode == "MASK") out.alpha_mode = AlphaMode::mask;
  else if (mode != "OPAQUE") value_error("material: alphaMode must be OPAQUE, MASK or BLEND, got '" + mode + "'");
  out.alpha_cutoff = factor(d, "alpha_cutoff", 0.0f, 1.0f);
  out.double_sided = d["double_sided"].cast<bool>();

  // Colour images (base colour, emission) are sRGB-encoded and data images linear, as glTF has them.
  const auto texture = [&](const char* key, const char* name, TexelEncoding encoding) {
    const py::object image = d[key];
    if (image.is_none()) return std::shared_ptr<const Texture>();
    if (!has_uvs) value_error(std::string("material: ") + name + " needs a mesh with uvs");
    return texture_of(image, std::string("material: ") + name, encoding);
  };
  out.diffuse_map = texture("base_color_texture", "baseColorTexture", TexelEncoding::srgb);
  out.metallic_roughness_map = texture("metallic_roughness_texture", "metallicRoughnessTexture", TexelEncoding::linear);
  out.emissive_map = texture("emissive_texture", "emissiveTexture", TexelEncoding::srgb);
  out.occlusion_map = texture("occlusion_texture", "occlusionTexture", TexelEncoding::linear);
  out.normal_map = texture("normal_texture", "normalTexture", TexelEncoding::linear);
  return out;
}

void make_sides_explicit(Mesh& mesh, const std::string& format) {
  if (format != "glTF" && format != "GLB")
    for (Material& m : mesh.materials) m.double_sided = false;
  const std::size_t triangles = mesh.triangle_count();
  bool unmaterialled = mesh.face_materials.size() != triangles;
  for (std::size_t t = 0; !unmaterialled && t < triangles; ++t) unmaterialled = mesh.face_materials[t] < 0;
  if (!unmaterialled) return;
  const auto fallback = static_cast<std::int32_t>(mesh.materials.size());
  mesh.materials.push_back(default_material());
  if (mesh.face_materials.size() != triangles) mesh.face_materials.assign(triangles, fallback);
  for (std::int32_t& m : mesh.face_materials)
    if (m < 0) m = fallback;
}

}  // namespace facet::python
