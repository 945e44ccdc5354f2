// pbr.hpp - PbrShader: glTF's metallic-roughness material lit by an environment and lights, tone-mapped.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <type_traits>

#include "facet/environment.hpp"
#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/brdf_layers.hpp"
#include "facet/shaders/masked.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/normal_mapping.hpp"
#include "facet/shaders/pbr_material.hpp"
#include "facet/shaders/punctual.hpp"
#include "facet/shaders/shadow_map.hpp"
#include "facet/simd.hpp"
#include "facet/texture.hpp"

namespace facet {

// The physically based look: radiance = emission + sum over lights of f(l, v) E_light NdotL + the environment's
// light by the split sum (brdf.hpp), then exposure, tone mapping and the sRGB encoding. Vertex colours arrive as
// displayed and are decoded per vertex. Lights are radiometric: a directional light's colour times intensity is
// the irradiance it gives a surface facing it, a point or spot light's falls off as punctual.hpp says; any number
// of them, the span pointing at the caller's array. Without an environment the ambient colour lights the diffuse
// part evenly.
//
// BasicPbrShader<true> (PbrShader) draws any material; BasicPbrShader<false> (UntexturedPbrShader) draws a material
// without textures the same, with neither uvs nor screen-space derivatives to interpolate; BasicPbrShader<true,
// true> (TangentPbrShader) draws a normal-mapped material of a mesh with tangents, its frame from them.

// What the physically based look interpolates: with both uv sets for a textured material, without them otherwise,
// with the tangent too for a mesh that has them.
template <bool kTextured, bool kTangents = false>
struct PbrVaryings {
  glm::vec3 world;
  glm::vec3 normal;  // world space, not normalized until the pixel
  glm::vec4 color;   // linear
  glm::vec2 uv;
  glm::vec2 uv1;  // the second set, for the maps that ask for it
};
template <>
struct PbrVaryings<false> {
  glm::vec3 world;
  glm::vec3 normal;
  glm::vec4 color;
};
template <>
struct PbrVaryings<true, true> {
  glm::vec3 world;
  glm::vec3 normal;
  glm::vec4 color;
  glm::vec2 uv;
  glm::vec2 uv1;
  glm::vec4 tangent;  // world space xyz, not normalized until the pixel; w the bitangent's sign (MeshVertex)
};

// The look's uniforms, shared by both shaders (UntexturedPbrShader{pbr_shader} copies them).
struct PbrUniforms {
  ObjectTransforms transforms{};
  PbrMaterial material{};
  std::span<const PunctualLight> lights{};
  glm::vec3 ambient{0.0f};  // linear; used only without an environment
  const Environment* environment = nullptr;
  glm::vec3 eye{0.0f};  // world space
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;
  // Screen-space ambient occlusion, 1 open to 0 occluded, per 2 x 2 pixels of the target, over a region of
  // width x height of them (top row first) whose first is at (x, y); multiplies the material's occlusion. Pixels
  // outside the region take its nearest value. nullptr: none.
  const float* screen_occlusion = nullptr;
  int screen_occlusion_x = 0, screen_occlusion_y = 0, screen_occlusion_width = 0, screen_occlusion_height = 0;
  // Each vertex's normal is the direction towards the eye: points without normals, as pyrender lights them.
  bool normal_towards_eye = false;
};

template <bool kTextured, bool kTangents = false>
struct BasicPbrShader : PbrUniforms {
  static_assert(kTextured || !kTangents, "tangents serve normal maps, which are textures");
  using Vertex = MeshVertex;
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = kTextured;  // texture level of detail and the normal map's frame
  using Varyings = PbrVaryings<kTextured, kTangents>;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    const float* decode = detail::srgb_decode_curve_table();
    const glm::vec4 color(detail::srgb_decode(v.color.r, decode), detail::srgb_decode(v.color.g, decode),
                          detail::srgb_decode(v.color.b, decode), v.color.a);
    const glm::vec3 world(transforms.world_from_object * p);
    const glm::vec3 normal = normal_towards_eye ? eye - world : transforms.normal_from_object * v.normal;
    if constexpr (kTangents) {
      // A tangent is a direction along the surface: it moves as positions do. A mirroring transform turns the
      // bitangent cross(normal, tangent) around, as in model.cpp's flattening.
      const glm::vec3 tangent = glm::mat3(transforms.world_from_object) * glm::vec3(v.tangent);
      const float sign = transforms.mirrored ? -v.tangent.w : v.tangent.w;
      return {transforms.clip_from_object * p, {world, normal, color, v.uv, v.uv1, glm::vec4(tangent, sign)}};
    } else if constexpr (kTextured) {
      return {transforms.clip_from_object * p, {world, normal, color, v.uv, v.uv1}};
    } else {
      return {transforms.clip_from_object * p, {world, normal, color}};
    }
  }

  // What the material is at one pixel.
  PbrInputs<float> inputs(const Fragment<Varyings>& f) const {
    const glm::vec4 c = material.pyrender_lighting ? glm::vec4(1.0f, 1.0f, 1.0f, f.varyings.color.a)
                                                       : f.varyings.color;
    PbrInputs<float> in = factor_inputs<float>(material, {c.r, c.g, c.b}, c.a);
    if (material.face_colors) multiply_face_color(material.face_colors[f.primitive], in);
    if constexpr (kTextured) {
      if (material.textured())
        multiply_textures(material, {{f.varyings.uv, f.varyings.uv1}, {f.ddx.uv, f.ddx.uv1}, {f.ddy.uv, f.ddy.uv1}},
                          in);
    }
    if (material.opaque) in.alpha = 1.0f;
    return in;
  }

  // Back faces are lit with the normal reversed (two-sided lighting, as glTF asks of double-sided materials). The
  // coat has the interpolated normal unless it has its own normal map (KHR_materials_clearcoat).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    glm::vec3 n = glm::normalize(f.varyings.normal);
    const bool front = transforms.front_side(f.front_facing);
    if (!front) n = -n;
    glm::vec3 n_coat = n;
    if constexpr (kTextured) {
      // The frame of the file's tangents, or the pixel's cotangent frame.
      const auto map = [&](const Texture& texture, float scale, std::uint32_t slot) {
        if constexpr (kTangents)
          return tangent_mapped_normal(n, f.varyings.tangent, front ? 1.0f : -1.0f, f, texture, material.sampler,
                                       scale, uvs_of(slot, material.uv1_maps));
        else return mapped_normal(n, f, texture, material.sampler, scale, uvs_of(slot, material.uv1_maps));
      };
      if (material.coated() && material.clearcoat_normal_map)
        n_coat = map(*material.clearcoat_normal_map, material.clearcoat_normal_scale, texture_slot::clearcoat_normal);
      if (material.normal_map) n = map(*material.normal_map, material.normal_scale, texture_slot::normal);
    }
    PbrInputs<float> in = inputs(f);
    if (screen_occlusion) in.occlusion = in.occlusion * screen_open(f.screen.x, f.screen.y);
    brdf::Rgb<float> radiance = shade(in, n, n_coat, f.varyings.world);
    if (material.pyrender_lighting) {
      const glm::vec4 c = f.varyings.color;
      radiance = radiance * brdf::Rgb<float>{c.r, c.g, c.b};
    }
    if (material.transmissive()) see_through(in, n, f.varyings.world, radiance);
    const brdf::Rgb<float> c = display(radiance);
    return {c.r, c.g, c.b, in.alpha};
  }

  // fragment() for 16 pixels, the same operations in the same order: the shading is one template for both
  // (shade()), and texture lookups are taken lane by lane with the scalar functions. A normal-mapped material is
  // shaded by fragment() lane by lane, and so is everything TangentPbrShader draws.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    if constexpr (kTangents) {
      return fragment_each_lane(*this, f);
    } else {
      using namespace simd;
      FACET_LANE_TYPES(L);
      if (material.bumped()) return fragment_each_lane(*this, f);
      Vec3 n = normalize(f.get(&Varyings::normal));
      const Mask back = transforms.mirrored ? f.front_facing : ~f.front_facing;
      n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
      PbrInputs<Float> in = inputs_lanes(f);
      if (screen_occlusion) {
        in.occlusion = in.occlusion * screen_open(f.screen_x, f.screen_y);
      }
      const Vec3 world = f.get(&Varyings::world);
      brdf::Rgb<Float> radiance = shade(in, n, n, world);
      if (material.pyrender_lighting) {
        const Color c = f.get(&Varyings::color);
        radiance = radiance * brdf::Rgb<Float>{c.r, c.g, c.b};
      }
      if (material.transmissive()) see_through(in, n, world, radiance);
      const brdf::Rgb<Float> out = display(radiance);
      return {out.r, out.g, out.b, in.alpha};
    }
  }

  // inputs() for 16 pixels: the same operations in the same order, face colours and textures lane by lane.
  template <class L>
  FACET_LANES_INLINE PbrInputs<simd::FloatT<L>> inputs_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Color c = f.get(&Varyings::color);
    const Float one = splat<L>(1.0f);
    PbrInputs<Float> in = material.pyrender_lighting ? factor_inputs<Float>(material, {one, one, one}, c.a)
                                                        : factor_inputs<Float>(material, {c.r, c.g, c.b}, c.a);
    if constexpr (kTextured) {
      if (material.face_colors || material.textured()) {
        const std::size_t u0 = FragmentLanes<Varyings>::float_index(&Varyings::uv);
        const std::size_t u1 = FragmentLanes<Varyings>::float_index(&Varyings::uv1);
        const LaneUvs<L> uvs{{f.get(&Varyings::uv), f.get(&Varyings::uv1)},
                          {{f.ddx[u0], f.ddx[u0 + 1]}, {f.ddx[u1], f.ddx[u1 + 1]}},
                          {{f.ddy[u0], f.ddy[u0 + 1]}, {f.ddy[u1], f.ddy[u1 + 1]}}};
        multiply_per_pixel(material, f.primitive, uvs, in, simd::lane_bits(f.active));
      }
    } else if (material.face_colors) {
      multiply_per_pixel(material, f.primitive, LaneUvs<L>{}, in);  // no textures: the uvs go unread
    }
    if (material.opaque) in.alpha = splat<L>(1.0f);
    return in;
  }

  // The scene-referred radiance towards the eye, for F = float (with glm::vec3) or simd::FloatT (with Vec3T):
  // the core BRDF under the lights and the environment, the sheen over it, the clear coat over both (three.js's
  // layering of KHR_materials_sheen and _clearcoat, emission included under the coat).
  template <class F, class V3>
  FACET_LANES_INLINE brdf::Rgb<F> shade(const PbrInputs<F>& in, const V3& n, const V3& n_coat,
                                        const V3& world) const {
    using brdf::Rgb;
    const brdf::Surface<F> s = surface_of(in);
    const V3 v = normalize(eye - world);
    const F n_dot_v = brdf::saturate(dot(n, v));
    const Layers<F> layer = layers(in, n_dot_v, n_coat, v);
    Rgb<F> lit = brdf::black<F>(), coat = brdf::black<F>();
    // Light from behind the surface reflects nothing, save through a sheen or a coat: without them it is skipped
    // (its shadow lookup too) where no pixel of the call faces it, and zeroed in the lanes that do not face it, so
    // that each pixel's sum is the same whichever way it is shaded.
    const bool plain = !material.sheened() && !material.coated();
    for (const PunctualLight& light : lights) {
      V3 l;
      F falloff;
      incident_light(light, world, l, falloff);
      const F n_dot_l = brdf::saturate(dot(n, l));
      if (plain && brdf::none_positive(n_dot_l)) continue;
      if (light.shadow) falloff = falloff * light.shadow->visibility<F>(world, n);
      const V3 h = normalize(v + l);
      const F n_dot_h = brdf::saturate(dot(n, h)), v_dot_h = brdf::saturate(dot(v, h));
      Rgb<F> r = brdf::reflect_light(s, n_dot_l, n_dot_v, n_dot_h, v_dot_h);
      if constexpr (!std::is_same_v<F, float>) {
        if (plain) {
          const F zero = brdf::constant<F>(0.0f);
          r = {brdf::select(n_dot_l > 0.0f, r.r, zero), brdf::select(n_dot_l > 0.0f, r.g, zero),
               brdf::select(n_dot_l > 0.0f, r.b, zero)};
        }
      }
      if (material.sheened()) {
        const F albedo = brdf::max(layer.sheen_albedo, brdf::sheen_albedo(n_dot_l, layer.sheen_roughness));
        r = r * (1.0f - layer.sheen_max * albedo) +
            in.sheen_color * brdf::reflect_sheen(n_dot_l, n_dot_v, n_dot_h, layer.sheen_alpha);
      }
      const glm::vec3 c = light.color;
      const Rgb<F> incident{c.r * falloff, c.g * falloff, c.b * falloff};
      lit = lit + r * incident;
      if (material.coated()) {
        const F coat_n_dot_l = brdf::saturate(dot(n_coat, l)), coat_n_dot_h = brdf::saturate(dot(n_coat, h));
        coat = coat + incident * brdf::reflect_coat(coat_n_dot_l, layer.coat_n_dot_v, coat_n_dot_h, v_dot_h,
                                                    layer.coat_alpha);
      }
    }
    Rgb<F> irradiance, radiance;
    F a, b;
    environment_terms(n, reflected(n, v, in.roughness), n_dot_v, in.roughness, irradiance, radiance, a, b);
    Rgb<F> ambient = brdf::reflect_environment(s, a, b, radiance, irradiance);
    if (material.sheened())
      ambient = ambient * (1.0f - layer.sheen_max * layer.sheen_albedo) +
                in.sheen_color * irradiance * (layer.sheen_albedo * (1.0f / brdf::kPi));
    if (material.pyrender_lighting) return in.emissive + (lit + ambient) * in.occlusion;
    const Rgb<F> color = in.emissive + lit + ambient * in.occlusion;
    if (!material.coated()) return color;
    if (environment) {
      const Rgb<F> l = radiance_along(reflected(n_coat, v, layer.coat_roughness), layer.coat_roughness);
      const auto ab = environment->split_sum(layer.coat_n_dot_v, layer.coat_roughness);
      coat = coat + l * ((brdf::kCoatF0 * ab.x + ab.y) * in.occlusion);
    }
    return color * brdf::coat_transmittance(in.clearcoat, layer.coat_n_dot_v) + coat * in.clearcoat;
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
  template <class L>
  FACET_LANES_INLINE static brdf::Rgb<simd::FloatT<L>> encode(const brdf::Rgb<simd::FloatT<L>>& c) {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const float* table = detail::srgb_encode_table();
    const auto channel = [table](const Float& linear) {
      const Float x = select(linear > 0.0f, select(linear < 1.0f, linear, splat<L>(1.0f)), splat<L>(0.0f));
      const Float f = x * static_cast<float>(detail::kSrgbEncodeSteps);
      Int i = truncate(f);
      i = blend(i < detail::kSrgbEncodeSteps, i, splat<L>(detail::kSrgbEncodeSteps - 1));
      const Float w = f - to_float(i);
      const std::array<Float, 2> t = gather_records<2>(table, i);  // entries i and i + 1
      return t[0] + (t[1] - t[0]) * w;
    };
    return {channel(c.r), channel(c.g), channel(c.b)};
  }

 private:
  // What the material reflects at a pixel. KHR_materials_specular: the dielectric's f0 coloured, kept at most 1
  // (the colour factor may exceed 1), then weighted by the strength, which is also its f90. What a transmissive
  // material lets through (see_through) is not reflected diffusely.
  template <class F>
  FACET_LANES_INLINE brdf::Surface<F> surface_of(const PbrInputs<F>& in) const {
    const auto f0 = [&](const F& color) {
      return brdf::min(color * material.dielectric_f0, brdf::constant<F>(1.0f)) * in.specular;
    };
    const brdf::Rgb<F> f0_dielectric{f0(in.specular_color.r), f0(in.specular_color.g), f0(in.specular_color.b)};
    brdf::Surface<F> s = brdf::surface(in.base, in.metallic, in.roughness, f0_dielectric, in.specular);
    if (material.transmissive()) s.c_diff = s.c_diff * (1.0f - passing(in));
    return s;
  }

  // The share of light a transmissive surface lets through untinted: what its transmission lets through times the
  // base colour's mean (a colour's absorption, which blending cannot tint the background with, is drawn as its
  // diffuse colour instead).
  template <class F>
  FACET_LANES_INLINE static F passing(const PbrInputs<F>& in) {
    return in.transmission * (1.0f - in.metallic) * ((in.base.r + in.base.g + in.base.b) * (1.0f / 3.0f));
  }

  // KHR_materials_transmission, approximated for a rasterizer without a second pass: the share of light a
  // transmissive surface lets through (passing) shows the surfaces behind it by alpha blending (unrefracted and
  // unblurred; thin-walled, so KHR_materials_volume changes nothing), and the share it reflects at this view angle
  // (its Fresnel term) covers them, or more where the reflection is brighter than white (a highlight). The
  // radiance is divided by that coverage, so that blending restores the reflection's strength.
  template <class F, class V3>
  FACET_LANES_INLINE void see_through(PbrInputs<F>& in, const V3& n, const V3& world, brdf::Rgb<F>& radiance) const {
    const brdf::Surface<F> s = surface_of(in);
    const F weight = brdf::schlick_weight(brdf::saturate(dot(n, normalize(eye - world))));
    const brdf::Rgb<F> fresnel{s.f0.r + (s.f90 - s.f0.r) * weight, s.f0.g + (s.f90 - s.f0.g) * weight,
                               s.f0.b + (s.f90 - s.f0.b) * weight};
    const F through = passing(in);
    const F highlight = brdf::min(brdf::max3(radiance) * exposure, brdf::constant<F>(1.0f));
    const F cover =
        brdf::max(brdf::max(1.0f - through * (1.0f - brdf::max3(fresnel)), highlight), brdf::constant<F>(1e-3f));
    radiance = radiance * (1.0f / cover);
    in.alpha = in.alpha * cover;
  }

  // The varying holding the uv set a map reads (a textured shader's).
  static glm::vec2 Varyings::*uvs_of(std::uint32_t slot, std::uint32_t uv1_maps) {
    return (uv1_maps & slot) ? &Varyings::uv1 : &Varyings::uv;
  }

  // What the sheen and the coat need at a pixel besides the lights (zero for a layer the material lacks).
  template <class F>
  struct Layers {
    F sheen_roughness, sheen_alpha, sheen_albedo, sheen_max;
    F coat_roughness, coat_alpha, coat_n_dot_v;
  };
  // The sheen's roughness kept in [1e-4, 1] and the coat's in [0.045, 1], as three.js keeps them, so that alpha
  // is never 0 and a glossy coat still shows a light's highlight.
  template <class F, class V3>
  FACET_LANES_INLINE Layers<F> layers(const PbrInputs<F>& in, const F& n_dot_v, const V3& n_coat, const V3& v) const {
    const F zero = brdf::constant<F>(0.0f), one = brdf::constant<F>(1.0f);
    Layers<F> out{zero, zero, zero, zero, zero, zero, zero};
    if (material.sheened()) {
      out.sheen_roughness = brdf::min(brdf::max(in.sheen_roughness, brdf::constant<F>(1e-4f)), one);
      out.sheen_alpha = out.sheen_roughness * out.sheen_roughness;
      out.sheen_albedo = brdf::sheen_albedo(n_dot_v, out.sheen_roughness);
      out.sheen_max = brdf::max3(in.sheen_color);
    }
    if (material.coated()) {
      out.coat_roughness = brdf::min(brdf::max(in.clearcoat_roughness, brdf::constant<F>(0.045f)), one);
      out.coat_alpha = out.coat_roughness * out.coat_roughness;
      out.coat_n_dot_v = brdf::saturate(dot(n_coat, v));
    }
    return out;
  }

  // The reflection of v about n, bent towards n as roughness grows (where the lobe's energy lies), as three.js
  // bends it.
  template <class F, class V3>
  FACET_LANES_INLINE static V3 reflected(const V3& n, const V3& v, const F& roughness) {
    const F alpha = roughness * roughness;
    const F k = alpha * alpha;
    const V3 mirror = n * (2.0f * dot(n, v)) - v;
    return normalize(mirror + (n - mirror) * k);
  }

  // The prefiltered environment along r at a roughness.
  brdf::Rgb<float> radiance_along(glm::vec3 r, float roughness) const {
    const glm::vec3 l = environment->radiance(r, roughness);
    return {l.r, l.g, l.b};
  }
  template <class L>
  FACET_LANES_INLINE brdf::Rgb<simd::FloatT<L>> radiance_along(const simd::Vec3T<L>& r,
                                                              const simd::FloatT<L>& roughness) const {
    const simd::Vec3T<L> l = environment->radiance(r, roughness);
    return {l.x, l.y, l.z};
  }

  // The screen-space occlusion at a pixel centre; pixels outside the region (helper lanes, the target's edges)
  // read its nearest column and row.
  float screen_open(float x, float y) const {
    const int column = std::clamp((static_cast<int>(x) >> 1) - screen_occlusion_x, 0, screen_occlusion_width - 1);
    const int row = std::clamp((static_cast<int>(y) >> 1) - screen_occlusion_y, 0, screen_occlusion_height - 1);
    return screen_occlusion[static_cast<std::size_t>(row) * static_cast<std::size_t>(screen_occlusion_width) +
                            static_cast<std::size_t>(column)];
  }
  template <class L>
  FACET_LANES_INLINE simd::FloatT<L> screen_open(const simd::FloatT<L>& x, const simd::FloatT<L>& y) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const auto within = [](const Int& v, int last) {
      const Int low = blend(v < last, v, splat<L>(last));
      return blend(low > 0, low, splat<L>(0));
    };
    const Int c = within((truncate(x) >> 1) - screen_occlusion_x, screen_occlusion_width - 1);
    const Int r = within((truncate(y) >> 1) - screen_occlusion_y, screen_occlusion_height - 1);
    return gather(screen_occlusion, r * screen_occlusion_width + c);
  }

  // E(n), the prefiltered radiance along r and the split-sum table, or, without an environment, the ambient colour
  // as a uniform environment: radiance `ambient` from every direction (irradiance pi * ambient), reflected by the
  // split sum's analytic fit (brdf::split_sum_approximation), so that metals reflect it too.
  template <class F, class V3>
  FACET_LANES_INLINE void environment_terms(const V3& n, const V3& r, const F& n_dot_v, const F& roughness,
                                            brdf::Rgb<F>& irradiance, brdf::Rgb<F>& radiance, F& a, F& b) const {
    if (!environment) {
      const glm::vec3 e = ambient * brdf::kPi;
      irradiance = {brdf::constant<F>(e.r), brdf::constant<F>(e.g), brdf::constant<F>(e.b)};
      radiance = {brdf::constant<F>(ambient.r), brdf::constant<F>(ambient.g), brdf::constant<F>(ambient.b)};
      brdf::split_sum_approximation(n_dot_v, roughness, a, b);
      return;
    }
    const std::array<F, 3> e = environment->irradiance(n.x, n.y, n.z);
    irradiance = {e[0], e[1], e[2]};
    radiance = radiance_along(r, roughness);
    const auto ab = environment->split_sum(n_dot_v, roughness);
    a = ab.x, b = ab.y;
  }
};

using PbrShader = BasicPbrShader<true>;
// PbrShader for a material without textures: the same picture with less to interpolate.
using UntexturedPbrShader = BasicPbrShader<false>;
// PbrShader for a normal-mapped material of a mesh with tangents (glTF TANGENT), per pixel.
using TangentPbrShader = BasicPbrShader<true, true>;

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::PbrShader);
FACET_EXTERN_SHADER(facet::UntexturedPbrShader);
FACET_EXTERN_SHADER(facet::TangentPbrShader);
FACET_EXTERN_SHADER(facet::Masked<facet::PbrShader>);
