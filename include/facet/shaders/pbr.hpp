// pbr.hpp - PbrShader: glTF's metallic-roughness material lit by an environment and lights, tone-mapped.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "facet/environment.hpp"
#include "facet/fragment_lanes.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/normal_mapping.hpp"
#include "facet/shaders/punctual.hpp"
#include "facet/shaders/shadow_map.hpp"
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
  const glm::vec4* face_colors = nullptr;   // as displayed, indexed by Fragment::primitive; nullptr = none
  const Texture* base_color_map = nullptr;  // sRGB-encoded
  const Texture* metallic_roughness_map = nullptr;
  const Texture* occlusion_map = nullptr;
  const Texture* emissive_map = nullptr;  // sRGB-encoded
  const Texture* normal_map = nullptr;
  const Texture* specular_map = nullptr;        // strength in alpha, multiplying specular
  const Texture* specular_color_map = nullptr;  // sRGB-encoded, multiplying specular_color
  float normal_scale = 1.0f;
  Sampler sampler{};
  bool opaque = false;  // alpha 1 whatever the inputs say (AlphaMode::opaque)

  bool textured() const {
    return base_color_map || metallic_roughness_map || occlusion_map || emissive_map || normal_map || specular_map ||
           specular_color_map;
  }
};

// The physically based look: radiance = emission + sum over lights of f(l, v) E_light NdotL + the environment's
// light by the split sum (brdf.hpp), then exposure, tone mapping and the sRGB encoding. Vertex colours arrive as
// displayed and are decoded per vertex. Lights are radiometric: a directional light's colour times intensity is
// the irradiance it gives a surface facing it, a point or spot light's falls off as punctual.hpp says; any number
// of them, the span pointing at the caller's array. Without an environment the ambient colour lights the diffuse
// part evenly.
struct PbrShader {
  using Vertex = MeshVertex;
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;  // texture level of detail and the normal map's frame

  struct Varyings {
    glm::vec3 world;
    glm::vec3 normal;  // world space, not normalized until the pixel
    glm::vec4 color;   // linear
    glm::vec2 uv;
  };

  ObjectTransforms transforms{};
  PbrMaterial material{};
  std::span<const PunctualLight> lights{};
  glm::vec3 ambient{0.0f};  // linear; used only without an environment
  const Environment* environment = nullptr;
  glm::vec3 eye{0.0f};  // world space
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;
  // Screen-space ambient occlusion, 1 open to 0 occluded, per 2 x 2 pixels of the target (width x height values,
  // top row first); multiplies the material's occlusion. nullptr: none.
  const float* screen_occlusion = nullptr;
  int screen_occlusion_width = 0, screen_occlusion_height = 0;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    const float* decode = detail::srgb_decode_curve_table();
    const glm::vec4 color(detail::srgb_decode(v.color.r, decode), detail::srgb_decode(v.color.g, decode),
                          detail::srgb_decode(v.color.b, decode), v.color.a);
    return {transforms.clip_from_object * p,
            {glm::vec3(transforms.world_from_object * p), transforms.normal_from_object * v.normal, color, v.uv}};
  }

  // What the material is at one pixel.
  template <class F>
  struct Inputs {
    brdf::Rgb<F> base;
    F alpha, metallic, roughness, occlusion;
    brdf::Rgb<F> emissive;
    F specular;  // KHR_materials_specular's strength and colour (linear)
    brdf::Rgb<F> specular_color;
  };

  Inputs<float> inputs(const Fragment<Varyings>& f) const {
    const PbrMaterial& m = material;
    const glm::vec4 c = f.varyings.color;
    Inputs<float> in{{m.base_color.r * c.r, m.base_color.g * c.g, m.base_color.b * c.b},
                     m.base_color.a * c.a,
                     m.metallic,
                     m.roughness,
                     1.0f,
                     {m.emissive.r, m.emissive.g, m.emissive.b},
                     m.specular,
                     {m.specular_color.r, m.specular_color.g, m.specular_color.b}};
    const float* decode = detail::srgb_decode_curve_table();
    const auto multiply_decoded = [&](glm::vec4 t) {
      in.base = in.base * brdf::Rgb<float>{detail::srgb_decode(t.r, decode), detail::srgb_decode(t.g, decode),
                                           detail::srgb_decode(t.b, decode)};
      in.alpha *= t.a;
    };
    if (m.face_colors) multiply_decoded(m.face_colors[f.primitive]);
    const glm::vec2 uv = f.varyings.uv, dx = f.ddx.uv, dy = f.ddy.uv;
    if (m.base_color_map) {
      const glm::vec4 t = m.base_color_map->sample_linear(uv, dx, dy, m.sampler);
      in.base = in.base * brdf::Rgb<float>{t.r, t.g, t.b};
      in.alpha *= t.a;
    }
    if (m.metallic_roughness_map) {
      const glm::vec4 t = m.metallic_roughness_map->sample(uv, dx, dy, m.sampler);
      in.roughness *= t.g;
      in.metallic *= t.b;
    }
    if (m.occlusion_map)
      in.occlusion = 1.0f + m.occlusion_strength * (m.occlusion_map->sample(uv, dx, dy, m.sampler).r - 1.0f);
    if (m.emissive_map) {
      const glm::vec4 t = m.emissive_map->sample_linear(uv, dx, dy, m.sampler);
      in.emissive = in.emissive * brdf::Rgb<float>{t.r, t.g, t.b};
    }
    if (m.specular_map) in.specular *= m.specular_map->sample(uv, dx, dy, m.sampler).a;
    if (m.specular_color_map) {
      const glm::vec4 t = m.specular_color_map->sample_linear(uv, dx, dy, m.sampler);
      in.specular_color = in.specular_color * brdf::Rgb<float>{t.r, t.g, t.b};
    }
    if (m.opaque) in.alpha = 1.0f;
    return in;
  }

  // Back faces are lit with the normal reversed (two-sided lighting, as glTF asks of double-sided materials).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    glm::vec3 n = glm::normalize(f.varyings.normal);
    if (!transforms.front_side(f.front_facing)) n = -n;
    if (material.normal_map) n = mapped_normal(n, f, *material.normal_map, material.sampler, material.normal_scale);
    Inputs<float> in = inputs(f);
    if (screen_occlusion)
      in.occlusion = in.occlusion * screen_open(f.screen.x, f.screen.y);
    const brdf::Rgb<float> c = display(shade(in, n, f.varyings.world));
    return {c.r, c.g, c.b, in.alpha};
  }

  // fragment() for 16 pixels, the same operations in the same order: the shading is one template for both
  // (shade()), and texture lookups are taken lane by lane with the scalar functions. A normal-mapped material is
  // shaded by fragment() lane by lane.
  FACET_LANES_INLINE simd::Color fragment_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    if (material.normal_map) return fragment_each_lane(*this, f);
    Vec3 n = normalize(f.get(&Varyings::normal));
    const Mask back = transforms.mirrored ? f.front_facing : ~f.front_facing;
    n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
    Inputs<Float> in = inputs_lanes(f);
    if (screen_occlusion) {
      Float open;
      for (int k = 0; k < kLanes; ++k) open[k] = screen_open(f.screen_x[k], f.screen_y[k]);
      in.occlusion = in.occlusion * open;
    }
    const brdf::Rgb<Float> out = display(shade(in, n, f.get(&Varyings::world)));
    return {out.r, out.g, out.b, in.alpha};
  }

  // inputs() for 16 pixels: the same operations in the same order, textures sampled lane by lane.
  FACET_LANES_INLINE Inputs<simd::Float> inputs_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    const PbrMaterial& m = material;
    const Color c = f.get(&Varyings::color);
    Inputs<Float> in{{m.base_color.r * c.r, m.base_color.g * c.g, m.base_color.b * c.b},
                     m.base_color.a * c.a,
                     splat(m.metallic),
                     splat(m.roughness),
                     splat(1.0f),
                     {splat(m.emissive.r), splat(m.emissive.g), splat(m.emissive.b)},
                     splat(m.specular),
                     {splat(m.specular_color.r), splat(m.specular_color.g), splat(m.specular_color.b)}};
    const float* decode = detail::srgb_decode_curve_table();
    const auto multiply_decoded = [&](int k, glm::vec4 t) {
      in.base.r[k] = in.base.r[k] * detail::srgb_decode(t.r, decode);
      in.base.g[k] = in.base.g[k] * detail::srgb_decode(t.g, decode);
      in.base.b[k] = in.base.b[k] * detail::srgb_decode(t.b, decode);
      in.alpha[k] *= t.a;
    };
    if (m.face_colors)
      for (int k = 0; k < kLanes; ++k) multiply_decoded(k, m.face_colors[f.primitive[k]]);
    if (m.textured()) {
      const Vec2 uv = f.get(&Varyings::uv);
      const std::size_t u = FragmentLanes<Varyings>::float_index(&Varyings::uv);
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec2 at(uv.x[k], uv.y[k]), dx(f.ddx[u][k], f.ddx[u + 1][k]), dy(f.ddy[u][k], f.ddy[u + 1][k]);
        if (m.base_color_map) {
          const glm::vec4 t = m.base_color_map->sample_linear(at, dx, dy, m.sampler);
          in.base.r[k] = in.base.r[k] * t.r;
          in.base.g[k] = in.base.g[k] * t.g;
          in.base.b[k] = in.base.b[k] * t.b;
          in.alpha[k] *= t.a;
        }
        if (m.metallic_roughness_map) {
          const glm::vec4 t = m.metallic_roughness_map->sample(at, dx, dy, m.sampler);
          in.roughness[k] *= t.g;
          in.metallic[k] *= t.b;
        }
        if (m.occlusion_map)
          in.occlusion[k] = 1.0f + m.occlusion_strength * (m.occlusion_map->sample(at, dx, dy, m.sampler).r - 1.0f);
        if (m.emissive_map) {
          const glm::vec4 t = m.emissive_map->sample_linear(at, dx, dy, m.sampler);
          in.emissive.r[k] = in.emissive.r[k] * t.r;
          in.emissive.g[k] = in.emissive.g[k] * t.g;
          in.emissive.b[k] = in.emissive.b[k] * t.b;
        }
        if (m.specular_map) in.specular[k] *= m.specular_map->sample(at, dx, dy, m.sampler).a;
        if (m.specular_color_map) {
          const glm::vec4 t = m.specular_color_map->sample_linear(at, dx, dy, m.sampler);
          in.specular_color.r[k] = in.specular_color.r[k] * t.r;
          in.specular_color.g[k] = in.specular_color.g[k] * t.g;
          in.specular_color.b[k] = in.specular_color.b[k] * t.b;
        }
      }
    }
    if (m.opaque) in.alpha = splat(1.0f);
    return in;
  }

  // The scene-referred radiance towards the eye, for F = float (with glm::vec3) or simd::Float (with simd::Vec3).
  template <class F, class V3>
  FACET_LANES_INLINE brdf::Rgb<F> shade(const Inputs<F>& in, const V3& n, const V3& world) const {
    using brdf::Rgb;
    // KHR_materials_specular: the dielectric's f0 coloured, kept at most 1 (the colour factor may exceed 1), then
    // weighted by the strength, which is also its f90.
    const auto f0 = [&](const F& color) {
      return brdf::min(color * material.dielectric_f0, brdf::constant<F>(1.0f)) * in.specular;
    };
    const brdf::Rgb<F> f0_dielectric{f0(in.specular_color.r), f0(in.specular_color.g), f0(in.specular_color.b)};
    const brdf::Surface<F> s = brdf::surface(in.base, in.metallic, in.roughness, f0_dielectric, in.specular);
    const V3 v = normalize(eye - world);
    const F n_dot_v_raw = dot(n, v);
    const F n_dot_v = brdf::saturate(n_dot_v_raw);
    Rgb<F> color = in.emissive;
    for (const PunctualLight& light : lights) {
      V3 l;
      F falloff;
      incident_light(light, world, l, falloff);
      if (light.shadow) falloff = falloff * light.shadow->visibility<F>(world, n);
      const V3 h = normalize(v + l);
      const F n_dot_l = brdf::saturate(dot(n, l));
      const Rgb<F> r = brdf::reflect_light(s, n_dot_l, n_dot_v, brdf::saturate(dot(n, h)), brdf::saturate(dot(v, h)));
      const glm::vec3 c = light.color;
      color = color + r * Rgb<F>{c.r * falloff, c.g * falloff, c.b * falloff};
    }
    Rgb<F> irradiance, radiance;
    F a, b;
    // The reflection, bent towards the normal as roughness grows (where the lobe's energy lies), as three.js does.
    const F alpha = in.roughness * in.roughness;
    const F k = alpha * alpha;
    const V3 mirror = n * (2.0f * n_dot_v_raw) - v;
    const V3 bent = normalize(mirror + (n - mirror) * k);
    environment_terms(n, bent, n_dot_v, in.roughness, irradiance, radiance, a, b);
    const Rgb<F> ambient = brdf::reflect_environment(s, a, b, radiance, irradiance);
    return color + ambient * in.occlusion;
  }

  // Exposure, tone mapping, then sRGB's encoding: the colour as displayed.
  template <class F>
  FACET_LANES_INLINE brdf::Rgb<F> display(const brdf::Rgb<F>& radiance) const {
    const brdf::Rgb<F> mapped = brdf::tone_map(radiance, tone_mapping, exposure);
    return encode(mapped);
  }

  // sRGB's encoding of a displayable linear colour, by table, per pixel or per lane.
  static brdf::Rgb<float> encode(const brdf::Rgb<float>& c) {
    const float* table = detail::srgb_encode_table();
    return {detail::srgb_encode(c.r, table), detail::srgb_encode(c.g, table), detail::srgb_encode(c.b, table)};
  }
  // detail::srgb_encode's operations in lanes, the two table entries gathered per lane.
  FACET_LANES_INLINE static brdf::Rgb<simd::Float> encode(const brdf::Rgb<simd::Float>& c) {
    using namespace simd;
    const float* table = detail::srgb_encode_table();
    const auto channel = [table](const Float& linear) {
      const Float x = select(linear > 0.0f, select(linear < 1.0f, linear, splat(1.0f)), splat(0.0f));
      const Float f = x * static_cast<float>(detail::kSrgbEncodeSteps);
      Int i = truncate(f);
      i = blend(i < detail::kSrgbEncodeSteps, i, splat(detail::kSrgbEncodeSteps - 1));
      const Float w = f - to_float(i);
      Float t0, t1;
      for (int k = 0; k < kLanes; ++k) t0[k] = table[i[k]], t1[k] = table[i[k] + 1];
      return t0 + (t1 - t0) * w;
    };
    return {channel(c.r), channel(c.g), channel(c.b)};
  }

 private:
  // The screen-space occlusion at a pixel centre; helper lanes past the target's edge read its last column or row.
  float screen_open(float x, float y) const {
    const int column = std::min(static_cast<int>(x) >> 1, screen_occlusion_width - 1);
    const int row = std::min(static_cast<int>(y) >> 1, screen_occlusion_height - 1);
    return screen_occlusion[static_cast<std::size_t>(row) * static_cast<std::size_t>(screen_occlusion_width) +
                            static_cast<std::size_t>(column)];
  }

  // E(n), the prefiltered radiance along r and the split-sum table, or, without an environment, the ambient colour
  // as a uniform irradiance of pi * ambient and no reflection.
  void environment_terms(glm::vec3 n, glm::vec3 r, float n_dot_v, float roughness, brdf::Rgb<float>& irradiance,
                         brdf::Rgb<float>& radiance, float& a, float& b) const {
    if (!environment) {
      const glm::vec3 e = ambient * brdf::kPi;
      irradiance = {e.r, e.g, e.b};
      radiance = {0.0f, 0.0f, 0.0f};
      a = b = 0.0f;
      return;
    }
    const std::array<float, 3> e = environment->irradiance(n.x, n.y, n.z);
    const glm::vec3 l = environment->radiance(r, roughness);
    const glm::vec2 ab = environment->split_sum(n_dot_v, roughness);
    irradiance = {e[0], e[1], e[2]};
    radiance = {l.r, l.g, l.b};
    a = ab.x, b = ab.y;
  }
  FACET_LANES_INLINE void environment_terms(const simd::Vec3& n, const simd::Vec3& r, const simd::Float& n_dot_v,
                                            const simd::Float& roughness, brdf::Rgb<simd::Float>& irradiance,
                                            brdf::Rgb<simd::Float>& radiance, simd::Float& a, simd::Float& b) const {
    if (!environment) {
      const glm::vec3 e = ambient * brdf::kPi;
      irradiance = {simd::splat(e.r), simd::splat(e.g), simd::splat(e.b)};
      radiance = {simd::splat(0.0f), simd::splat(0.0f), simd::splat(0.0f)};
      a = b = simd::splat(0.0f);
      return;
    }
    const std::array<simd::Float, 3> e = environment->irradiance(n.x, n.y, n.z);
    irradiance = {e[0], e[1], e[2]};
    const simd::Vec3 l = environment->radiance(r, roughness);
    radiance = {l.x, l.y, l.z};
    const simd::Vec2 ab = environment->split_sum(n_dot_v, roughness);
    a = ab.x, b = ab.y;
  }

};

// PbrShader for a material without textures: the same picture without the screen-space derivatives.
struct UntexturedPbrShader : PbrShader {
  static constexpr bool needs_derivatives = false;
};

}  // namespace facet
