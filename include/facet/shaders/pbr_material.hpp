// pbr_material.hpp - PbrMaterial and what it is at one pixel: glTF's material factors times its textures.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"
#include "facet/texture.hpp"

namespace facet {

// One material's inputs, in linear light (Material holds colours as displayed; the scene decodes them once).
struct PbrMaterial {
  glm::vec4 base_color{1.0f};  // linear RGB, alpha
  float metallic = 0.0f, roughness = 0.5f;
  glm::vec3 emissive{0.0f};
  float occlusion_strength = 1.0f;
  // The dielectric's reflectance (KHR_materials_ior: brdf::dielectric_f0 of its ior; 0.04 for ior 1.5), and
  // KHR_materials_specular's strength and linear colour, which scale it.
  float dielectric_f0 = 0.04f;
  float specular = 1.0f;
  glm::vec3 specular_color{1.0f};
  // KHR_materials_clearcoat: the coat's strength and roughness (0 strength: no coat), and KHR_materials_sheen's
  // linear colour and roughness (black: no sheen).
  float clearcoat = 0.0f, clearcoat_roughness = 0.0f;
  glm::vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  const glm::vec4* face_colors = nullptr;   // as displayed, indexed by Fragment::primitive; nullptr = none
  const Texture* base_color_map = nullptr;  // sRGB-encoded
  const Texture* metallic_roughness_map = nullptr;
  const Texture* occlusion_map = nullptr;
  const Texture* emissive_map = nullptr;  // sRGB-encoded
  const Texture* normal_map = nullptr;
  const Texture* specular_map = nullptr;        // strength in alpha, multiplying specular
  const Texture* specular_color_map = nullptr;  // sRGB-encoded, multiplying specular_color
  const Texture* clearcoat_map = nullptr;            // red multiplies clearcoat
  const Texture* clearcoat_roughness_map = nullptr;  // green multiplies clearcoat_roughness
  const Texture* clearcoat_normal_map = nullptr;     // the coat's own normal map; none: the coat is not bumped
  const Texture* sheen_color_map = nullptr;          // sRGB-encoded, multiplying sheen_color
  const Texture* sheen_roughness_map = nullptr;      // alpha multiplies sheen_roughness
  float normal_scale = 1.0f, clearcoat_normal_scale = 1.0f;
  Sampler sampler{};
  bool opaque = false;  // alpha 1 whatever the inputs say (AlphaMode::opaque)

  bool textured() const {
    return base_color_map || metallic_roughness_map || occlusion_map || emissive_map || normal_map || specular_map ||
           specular_color_map || clearcoat_map || clearcoat_roughness_map || clearcoat_normal_map ||
           sheen_color_map || sheen_roughness_map;
  }
  bool coated() const { return clearcoat > 0.0f; }
  bool sheened() const { return sheen_color.r > 0.0f || sheen_color.g > 0.0f || sheen_color.b > 0.0f; }
  // Lane shading takes one normal per pixel from the interpolated one; a normal map sends the pixel to fragment().
  bool bumped() const { return normal_map || (coated() && clearcoat_normal_map); }
};

// What the material is at one pixel (F = float) or at 16 (F = simd::Float).
template <class F>
struct PbrInputs {
  brdf::Rgb<F> base;
  F alpha, metallic, roughness, occlusion;
  brdf::Rgb<F> emissive;
  F specular;  // KHR_materials_specular's strength and colour (linear)
  brdf::Rgb<F> specular_color;
  F clearcoat, clearcoat_roughness;
  brdf::Rgb<F> sheen_color;
  F sheen_roughness;

  // op(x, y) on each pair of numbers of this and `other` (every F of the struct, in order).
  template <class G, class Op>
  FACET_LANES_INLINE void each_number(PbrInputs<G>& other, Op op) {
    const auto rgb = [&](brdf::Rgb<F>& a, brdf::Rgb<G>& b) { op(a.r, b.r), op(a.g, b.g), op(a.b, b.b); };
    rgb(base, other.base);
    op(alpha, other.alpha), op(metallic, other.metallic), op(roughness, other.roughness);
    op(occlusion, other.occlusion);
    rgb(emissive, other.emissive);
    op(specular, other.specular);
    rgb(specular_color, other.specular_color);
    op(clearcoat, other.clearcoat), op(clearcoat_roughness, other.clearcoat_roughness);
    rgb(sheen_color, other.sheen_color);
    op(sheen_roughness, other.sheen_roughness);
  }
};

// The material's factors times a linear vertex colour and a face colour (as displayed), before its textures.
template <class F>
FACET_LANES_INLINE PbrInputs<F> factor_inputs(const PbrMaterial& m, const brdf::Rgb<F>& color, const F& alpha) {
  const auto c = [](float v) { return brdf::constant<F>(v); };
  const auto rgb = [&](glm::vec3 v) { return brdf::Rgb<F>{c(v.r), c(v.g), c(v.b)}; };
  return {{color.r * m.base_color.r, color.g * m.base_color.g, color.b * m.base_color.b},
          alpha * m.base_color.a,
          c(m.metallic),
          c(m.roughness),
          c(1.0f),
          rgb(m.emissive),
          c(m.specular),
          rgb(m.specular_color),
          c(m.clearcoat),
          c(m.clearcoat_roughness),
          rgb(m.sheen_color),
          c(m.sheen_roughness)};
}

// A face colour (as displayed) multiplied into the base colour and alpha.
inline void multiply_face_color(glm::vec4 displayed, PbrInputs<float>& in) {
  const float* decode = detail::srgb_decode_curve_table();
  in.base = in.base * brdf::Rgb<float>{detail::srgb_decode(displayed.r, decode),
                                       detail::srgb_decode(displayed.g, decode),
                                       detail::srgb_decode(displayed.b, decode)};
  in.alpha *= displayed.a;
}

// The material's textures at one pixel, multiplied into its inputs as glTF and its extensions define them.
inline void multiply_textures(const PbrMaterial& m, glm::vec2 uv, glm::vec2 dx, glm::vec2 dy, PbrInputs<float>& in) {
  const auto linear_rgb = [&](const Texture& map, brdf::Rgb<float>& into) {
    const glm::vec4 t = map.sample_linear(uv, dx, dy, m.sampler);
    into = into * brdf::Rgb<float>{t.r, t.g, t.b};
    return t;
  };
  if (m.base_color_map) in.alpha *= linear_rgb(*m.base_color_map, in.base).a;
  if (m.metallic_roughness_map) {
    const glm::vec4 t = m.metallic_roughness_map->sample(uv, dx, dy, m.sampler);
    in.roughness *= t.g;
    in.metallic *= t.b;
  }
  if (m.occlusion_map)
    in.occlusion = 1.0f + m.occlusion_strength * (m.occlusion_map->sample(uv, dx, dy, m.sampler).r - 1.0f);
  if (m.emissive_map) linear_rgb(*m.emissive_map, in.emissive);
  if (m.specular_map) in.specular *= m.specular_map->sample(uv, dx, dy, m.sampler).a;
  if (m.specular_color_map) linear_rgb(*m.specular_color_map, in.specular_color);
  if (m.clearcoat_map) in.clearcoat *= m.clearcoat_map->sample(uv, dx, dy, m.sampler).r;
  if (m.clearcoat_roughness_map)
    in.clearcoat_roughness *= m.clearcoat_roughness_map->sample(uv, dx, dy, m.sampler).g;
  if (m.sheen_color_map) linear_rgb(*m.sheen_color_map, in.sheen_color);
  if (m.sheen_roughness_map) in.sheen_roughness *= m.sheen_roughness_map->sample(uv, dx, dy, m.sampler).a;
}

// The same per-pixel steps for 16 lanes, lane by lane with the scalar functions, so both paths agree exactly.
// `primitive` is read only with face colours; `dx` and `dy` are the uvs' derivatives.
FACET_LANES_INLINE void multiply_per_pixel(const PbrMaterial& m, const simd::UInt& primitive, const simd::Vec2& uv,
                                           const simd::Vec2& dx, const simd::Vec2& dy, PbrInputs<simd::Float>& in) {
  for (int k = 0; k < simd::kLanes; ++k) {
    PbrInputs<float> one;
    in.each_number(one, [k](simd::Float& lanes, float& v) { v = lanes[k]; });
    if (m.face_colors) multiply_face_color(m.face_colors[primitive[k]], one);
    if (m.textured())
      multiply_textures(m, {uv.x[k], uv.y[k]}, {dx.x[k], dx.y[k]}, {dy.x[k], dy.y[k]}, one);
    in.each_number(one, [k](simd::Float& lanes, float& v) { lanes[k] = v; });
  }
}

}  // namespace facet
