// pbr_material.hpp - PbrMaterial and what it is at one pixel: glTF's material factors times its textures.
#pragma once

#include <bit>
#include <cstdint>

#include <glm/glm.hpp>

#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"
#include "facet/texture.hpp"
#include "facet/texture_slots.hpp"

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
  float transmission = 0.0f;  // KHR_materials_transmission's factor (0: opaque dielectric)
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
  const Texture* transmission_map = nullptr;         // red multiplies transmission
  float normal_scale = 1.0f, clearcoat_normal_scale = 1.0f;
  std::uint32_t uv1_maps = 0;  // the maps that read the second uv set, as texture_slot bits
  Sampler sampler{};
  bool opaque = false;  // alpha 1 whatever the inputs say (AlphaMode::opaque)
  bool pyrender_lighting = false;  // Material::pyrender_lighting

  bool textured() const {
    return base_color_map || metallic_roughness_map || occlusion_map || emissive_map || normal_map || specular_map ||
           specular_color_map || clearcoat_map || clearcoat_roughness_map || clearcoat_normal_map ||
           sheen_color_map || sheen_roughness_map || transmission_map;
  }
  bool coated() const { return clearcoat > 0.0f; }
  bool sheened() const { return sheen_color.r > 0.0f || sheen_color.g > 0.0f || sheen_color.b > 0.0f; }
  bool transmissive() const { return transmission > 0.0f; }
  // Lane shading takes one normal per pixel from the interpolated one; a normal map sends the pixel to fragment().
  bool bumped() const { return normal_map || (coated() && clearcoat_normal_map); }
};

// What the material is at one pixel (F = float) or at 16 (F = simd::FloatT of a lane layout).
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
  F transmission;

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
    op(transmission, other.transmission);
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
          c(m.sheen_roughness),
          c(m.transmission)};
}

// A face colour (as displayed) multiplied into the base colour and alpha.
inline void multiply_face_color(glm::vec4 displayed, PbrInputs<float>& in) {
  const float* decode = detail::srgb_decode_curve_table();
  in.base = in.base * brdf::Rgb<float>{detail::srgb_decode(displayed.r, decode),
                                       detail::srgb_decode(displayed.g, decode),
                                       detail::srgb_decode(displayed.b, decode)};
  in.alpha *= displayed.a;
}

// The texture coordinates of one pixel in both sets, with their screen-space derivatives.
struct PixelUvs {
  glm::vec2 uv[2], dx[2], dy[2];
};

// A texel's four channels, for one pixel or for 16 lanes.
template <class F>
struct TexelsOf {
  F r, g, b, a;
};

// The material's textures multiplied into its inputs, as glTF and its extensions define them, for one pixel
// (F = float) or 16 lanes: sample(map, slot, linear) reads a map with the uv set the material gives it, in linear
// light (linear true: colour maps) or as stored.
template <class F, class Sample>
FACET_LANES_INLINE void multiply_textures(const PbrMaterial& m, Sample&& sample, PbrInputs<F>& in) {
  const auto linear_rgb = [&](const Texture& map, std::uint32_t slot, brdf::Rgb<F>& into)
                              __attribute__((always_inline)) {
    const TexelsOf<F> t = sample(map, slot, true);
    into = into * brdf::Rgb<F>{t.r, t.g, t.b};
    return t;
  };
  namespace slot = texture_slot;
  if (m.base_color_map) in.alpha = in.alpha * linear_rgb(*m.base_color_map, slot::base_color, in.base).a;
  if (m.metallic_roughness_map) {
    const TexelsOf<F> t = sample(*m.metallic_roughness_map, slot::metallic_roughness, false);
    in.roughness = in.roughness * t.g;
    in.metallic = in.metallic * t.b;
  }
  if (m.occlusion_map)
    in.occlusion = 1.0f + m.occlusion_strength * (sample(*m.occlusion_map, slot::occlusion, false).r - 1.0f);
  if (m.emissive_map) linear_rgb(*m.emissive_map, slot::emissive, in.emissive);
  if (m.specular_map) in.specular = in.specular * sample(*m.specular_map, slot::specular, false).a;
  if (m.specular_color_map) linear_rgb(*m.specular_color_map, slot::specular_color, in.specular_color);
  if (m.clearcoat_map) in.clearcoat = in.clearcoat * sample(*m.clearcoat_map, slot::clearcoat, false).r;
  if (m.clearcoat_roughness_map)
    in.clearcoat_roughness =
        in.clearcoat_roughness * sample(*m.clearcoat_roughness_map, slot::clearcoat_roughness, false).g;
  if (m.sheen_color_map) linear_rgb(*m.sheen_color_map, slot::sheen_color, in.sheen_color);
  if (m.sheen_roughness_map)
    in.sheen_roughness = in.sheen_roughness * sample(*m.sheen_roughness_map, slot::sheen_roughness, false).a;
  if (m.transmission_map) in.transmission = in.transmission * sample(*m.transmission_map, slot::transmission, false).r;
}

// One pixel's texel of a map, with the uv set the material gives the map's slot.
inline glm::vec4 sample_map(const PbrMaterial& m, const Texture& map, std::uint32_t slot, bool linear,
                            const PixelUvs& at) {
  const int set = (m.uv1_maps & slot) ? 1 : 0;
  return linear ? map.sample_linear(at.uv[set], at.dx[set], at.dy[set], m.sampler)
                : map.sample(at.uv[set], at.dx[set], at.dy[set], m.sampler);
}

// The material's textures at one pixel.
inline void multiply_textures(const PbrMaterial& m, const PixelUvs& at, PbrInputs<float>& in) {
  multiply_textures<float>(
      m,
      [&](const Texture& map, std::uint32_t slot, bool linear) {
        const glm::vec4 t = sample_map(m, map, slot, linear, at);
        return TexelsOf<float>{t.r, t.g, t.b, t.a};
      },
      in);
}

// PixelUvs for 16 lanes.
template <class L>
struct LaneUvs {
  simd::Vec2T<L> uv[2], dx[2], dy[2];
  PixelUvs lane(int k) const {
    PixelUvs out;
    for (int s = 0; s < 2; ++s) {
      out.uv[s] = {uv[s].x[k], uv[s].y[k]};
      out.dx[s] = {dx[s].x[k], dx[s].y[k]};
      out.dy[s] = {dy[s].x[k], dy[s].y[k]};
    }
    return out;
  }
};

// The same per-pixel steps for 16 lanes, with the scalar functions, so both paths agree exactly: each lane's face
// colour, then each map's texels lane by lane, multiplied in as the lanes' values (an input is multiplied by the
// same numbers in the same order as per pixel). `primitive` is read only with face colours. Maps read lane by lane
// are read in the lanes set in `lanes` only (the pixels the call colours: on a multisampled edge, a shading round
// may colour a few of them), and give the others 0.
template <class L>
FACET_LANES_INLINE void multiply_per_pixel(const PbrMaterial& m, const simd::UIntT<L>& primitive,
                                           const LaneUvs<L>& uvs, PbrInputs<simd::FloatT<L>>& in,
                                           unsigned lanes = Texture::kAllLanes) {
  using Float = simd::FloatT<L>;
  if (m.face_colors)
    for (int k = 0; k < simd::kLanes; ++k) {
      PbrInputs<float> one;
      one.base = {in.base.r[k], in.base.g[k], in.base.b[k]};
      one.alpha = in.alpha[k];
      multiply_face_color(m.face_colors[primitive[k]], one);
      in.base.r[k] = one.base.r, in.base.g[k] = one.base.g, in.base.b[k] = one.base.b;
      in.alpha[k] = one.alpha;
    }
  if (!m.textured()) return;
  // Lambdas in lane code are forced inline: one left out of line would be compiled for the baseline only.
  multiply_textures<Float>(
      m,
      [&](const Texture& map, std::uint32_t slot, bool linear) __attribute__((always_inline)) {
        TexelsOf<Float> t;
        if (linear) {
          const int set = (m.uv1_maps & slot) ? 1 : 0;
          const simd::ColorT<L> c =
              map.sample_linear_lanes(uvs.uv[set], uvs.dx[set], uvs.dy[set], m.sampler, lanes);
          return TexelsOf<Float>{c.r, c.g, c.b, c.a};
        }
        t = {Float{}, Float{}, Float{}, Float{}};
        for (unsigned left = lanes; left; left &= left - 1) {
          const int k = std::countr_zero(left);
          const glm::vec4 texel = sample_map(m, map, slot, linear, uvs.lane(k));
          t.r[k] = texel.r, t.g[k] = texel.g, t.b[k] = texel.b, t.a[k] = texel.a;
        }
        return t;
      },
      in);
}

}  // namespace facet
