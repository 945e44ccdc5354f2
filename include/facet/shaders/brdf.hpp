// brdf.hpp - glTF's metallic-roughness BRDF (glTF 2.0, Appendix B) and tone mapping, for one pixel or 16 lanes.
#pragma once

#include <cmath>
#include <type_traits>

#include "facet/simd.hpp"

namespace facet {

// How scene-referred light becomes a displayable colour in [0, 1] (before sRGB encoding).
enum class ToneMapping {
  none,     // clamped
  neutral,  // Khronos PBR Neutral: colours kept as they are up to 0.76, highlights compressed and desaturated
  aces,     // ACES filmic, Stephen Hill's fit of the RRT and ODT, as three.js applies it (exposure / 0.6)
};

}  // namespace facet

namespace facet::brdf {

// Every function below is a template on F, float for one pixel or simd::FloatT for 16, built from the same
// operations in the same order, so that a shader's scalar and lane paths give identical images. Only exact IEEE
// operations are used (+, -, *, /, sqrt, comparisons), so every CPU and the browser round alike.

// A constant as F: the float itself, or broadcast to every lane.
template <class F>
FACET_LANES_INLINE F constant(float v) {
  if constexpr (std::is_same_v<F, float>) {
    return v;
  } else {
    return simd::splat<typename F::layout>(v);
  }
}
inline float select(bool m, float a, float b) { return m ? a : b; }
using simd::select;
inline float sqrt(float v) { return std::sqrt(v); }
using simd::sqrt;
inline float floor(float v) { return std::floor(v); }
using simd::floor;
// std::max's and std::min's comparisons (NaN handled as they handle it).
template <class F>
FACET_LANES_INLINE F max(const F& a, const F& b) {
  return select(a < b, b, a);
}
template <class F>
FACET_LANES_INLINE F min(const F& a, const F& b) {
  return select(b < a, b, a);
}
template <class F>
FACET_LANES_INLINE F abs(const F& v) {
  return select(v < 0.0f, -v, v);
}
template <class F>
FACET_LANES_INLINE F saturate(const F& v) {
  return min(max(v, constant<F>(0.0f)), constant<F>(1.0f));
}

// Whether no pixel (or lane) of v lies above 0; NaN does not.
inline bool none_positive(float v) { return !(v > 0.0f); }
template <class F>
FACET_LANES_INLINE bool none_positive(const F& v) {
  return simd::lane_bits(v > 0.0f) == 0;
}

inline constexpr float kPi = 3.14159265358979f;

// A linear RGB colour, per pixel or per lane.
template <class F>
struct Rgb {
  F r, g, b;
  FACET_LANES_INLINE friend Rgb operator+(const Rgb& x, const Rgb& y) { return {x.r + y.r, x.g + y.g, x.b + y.b}; }
  FACET_LANES_INLINE friend Rgb operator*(const Rgb& x, const Rgb& y) { return {x.r * y.r, x.g * y.g, x.b * y.b}; }
  FACET_LANES_INLINE friend Rgb operator*(const Rgb& x, const F& s) { return {x.r * s, x.g * s, x.b * s}; }
};

// No light, per pixel or per lane.
template <class F>
FACET_LANES_INLINE Rgb<F> black() {
  return {constant<F>(0.0f), constant<F>(0.0f), constant<F>(0.0f)};
}

// The microfacet distribution D: Trowbridge-Reitz (GGX), alpha = roughness^2.
//   D = alpha^2 / (pi (NdotH^2 (alpha^2 - 1) + 1)^2)
template <class F>
FACET_LANES_INLINE F distribution_ggx(const F& n_dot_h, const F& alpha) {
  const F alpha2 = alpha * alpha;
  const F f = n_dot_h * n_dot_h * (alpha2 - 1.0f) + 1.0f;
  return alpha2 / (kPi * f * f);
}

// Smith's height-correlated visibility V = G / (4 |NdotL| |NdotV|):
//   V = 0.5 / (NdotL sqrt(NdotV^2 (1 - alpha^2) + alpha^2) + NdotV sqrt(NdotL^2 (1 - alpha^2) + alpha^2))
// Zero where the denominator is (grazing on both sides).
template <class F>
FACET_LANES_INLINE F visibility_smith_ggx(const F& n_dot_l, const F& n_dot_v, const F& alpha) {
  const F alpha2 = alpha * alpha;
  const F ggx_v = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0f - alpha2) + alpha2);
  const F ggx_l = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0f - alpha2) + alpha2);
  const F sum = ggx_v + ggx_l;
  return select(sum > 0.0f, 0.5f / sum, constant<F>(0.0f));
}

// Schlick's Fresnel weight (1 - |VdotH|)^5: F = f0 + (f90 - f0) * weight.
template <class F>
FACET_LANES_INLINE F schlick_weight(const F& v_dot_h) {
  const F m = saturate(1.0f - v_dot_h);
  const F m2 = m * m;
  return m2 * m2 * m;
}

// The dielectric's reflectance at normal incidence for an index of refraction (KHR_materials_ior):
// ((ior - 1) / (ior + 1))^2, 1 for ior 0 (the extension's specular-glossiness mode, Fresnel 1 everywhere). Worked
// in double so that the default 1.5 gives exactly 0.04f, the constant the core specification uses.
inline float dielectric_f0(float ior) {
  const double r = (static_cast<double>(ior) - 1.0) / (static_cast<double>(ior) + 1.0);
  return static_cast<float>(r * r);
}

// What a metallic-roughness material reflects, from its glTF inputs (Appendix B, "Metal BRDF and dielectric BRDF",
// with KHR_materials_specular's dielectric f0 and f90):
//   c_diff = lerp(baseColor, black, metallic), f0 = lerp(f0_dielectric, baseColor, metallic),
//   f90 = lerp(f90_dielectric, 1, metallic), alpha = roughness^2
// f0_diffuse is f0 with the dielectric part's largest channel for every channel: the diffuse part loses what the
// dielectric's Fresnel term reflects at its strongest (the extension's max_value), so a coloured specular takes no
// complementary colour out of the diffuse. With a grey dielectric f0 it equals f0.
template <class F>
struct Surface {
  Rgb<F> c_diff, f0, f0_diffuse;
  F f90, roughness, alpha;
};
// f0_dielectric = min(f0(ior) specularColor, 1) specular, f90_dielectric = specular. The defaults (0.04 and 1)
// give the core specification's material with the same operations, so its pictures do not change.
template <class F>
FACET_LANES_INLINE Surface<F> surface(const Rgb<F>& base_color, const F& metallic, const F& roughness,
                                      const Rgb<F>& f0_dielectric, const F& f90_dielectric) {
  const F dielectric = 1.0f - metallic;
  const F grey = max(max(f0_dielectric.r, f0_dielectric.g), f0_dielectric.b) * dielectric;
  return {{base_color.r * dielectric, base_color.g * dielectric, base_color.b * dielectric},
          {f0_dielectric.r * dielectric + base_color.r * metallic,
           f0_dielectric.g * dielectric + base_color.g * metallic,
           f0_dielectric.b * dielectric + base_color.b * metallic},
          {grey + base_color.r * metallic, grey + base_color.g * metallic, grey + base_color.b * metallic},
          // 1 - (1 - metallic)(1 - specular): exactly 1 when specular is 1, whatever the metallic.
          1.0f - dielectric * (1.0f - f90_dielectric),
          roughness,
          roughness * roughness};
}
template <class F>
FACET_LANES_INLINE Surface<F> surface(const Rgb<F>& base_color, const F& metallic, const F& roughness) {
  const F f0 = constant<F>(0.04f);
  return surface(base_color, metallic, roughness, Rgb<F>{f0, f0, f0}, constant<F>(1.0f));
}

// f(l, v) |NdotL| for one light direction (Appendix B's sample implementation):
//   F = f0 + (f90 - f0) (1 - |VdotH|)^5
//   f_diffuse = (1 - F') c_diff / pi,   f_specular = F D V      (F': F with f0_diffuse)
// The caller multiplies by the light's colour and intensity. n_dot_l and n_dot_v clamped to [0, 1] by the caller.
template <class F>
FACET_LANES_INLINE Rgb<F> reflect_light(const Surface<F>& s, const F& n_dot_l, const F& n_dot_v, const F& n_dot_h,
                                        const F& v_dot_h) {
  const F weight = schlick_weight(v_dot_h);
  const F dv = distribution_ggx(n_dot_h, s.alpha) * visibility_smith_ggx(n_dot_l, n_dot_v, s.alpha);
  const auto channel = [&](const F& c_diff, const F& f0, const F& f0_diffuse) {
    const F fresnel = f0 + (s.f90 - f0) * weight;
    const F diffuse_fresnel = f0_diffuse + (s.f90 - f0_diffuse) * weight;
    return ((1.0f - diffuse_fresnel) * c_diff * (1.0f / kPi) + fresnel * dv) * n_dot_l;
  };
  return {channel(s.c_diff.r, s.f0.r, s.f0_diffuse.r), channel(s.c_diff.g, s.f0.g, s.f0_diffuse.g),
          channel(s.c_diff.b, s.f0.b, s.f0_diffuse.b)};
}

// Image-based light by the split sum, with Fdez-Aguera's multiple-scattering term ("A Multiple-Scattering
// Microfacet Model for Real-Time Image-based Lighting", 2019), as three.js does it:
//   FssEss = f0 A + f90 B      (A, B: the split-sum table at NdotV and roughness)
//   Ems = 1 - (A + B),  Favg = f0 + (1 - f0) / 21,  Fms = FssEss Favg / (1 - Ems Favg)
//   specular = FssEss radiance + Fms Ems irradiance / pi
//   diffuse  = c_diff (1 - max(FssEss + Fms Ems)) irradiance / pi
// `irradiance` is the cosine-weighted irradiance E(n); `radiance` the prefiltered environment along the reflection.
template <class F>
FACET_LANES_INLINE Rgb<F> reflect_environment(const Surface<F>& s, const F& a, const F& b, const Rgb<F>& radiance,
                                              const Rgb<F>& irradiance) {
  const F e_ms = 1.0f - (a + b);
  const auto scatter = [&](const F& f0, F& single) {
    single = f0 * a + s.f90 * b;
    const F f_avg = f0 + (1.0f - f0) * (1.0f / 21.0f);
    // Kept off zero: a white metal (f_avg 1) with no environment (a = b = 0, e_ms 1) would give 0 / 0.
    return single * f_avg / max(1.0f - e_ms * f_avg, constant<F>(1e-6f)) * e_ms;
  };
  Rgb<F> single, multi;
  multi.r = scatter(s.f0.r, single.r);
  multi.g = scatter(s.f0.g, single.g);
  multi.b = scatter(s.f0.b, single.b);
  const F total = max(max(single.r + multi.r, single.g + multi.g), single.b + multi.b);
  const F diffuse = 1.0f - total;
  const auto channel = [&](const F& c_diff, const F& ss, const F& ms, const F& l, const F& e) {
    const F e_over_pi = e * (1.0f / kPi);
    return ss * l + ms * e_over_pi + c_diff * diffuse * e_over_pi;
  };
  return {channel(s.c_diff.r, single.r, multi.r, radiance.r, irradiance.r),
          channel(s.c_diff.g, single.g, multi.g, radiance.g, irradiance.g),
          channel(s.c_diff.b, single.b, multi.b, radiance.b, irradiance.b)};
}

// The split sum's second factor, (A, B) with the reflected share f0 A + f90 B, by Karis' analytic fit of the
// table for GGX ("Physically Based Shading on Mobile", 2014): for light that is the same from every direction,
// where no prefiltered environment is worth its table.
template <class F>
FACET_LANES_INLINE void split_sum_approximation(const F& n_dot_v, const F& roughness, F& a, F& b) {
  const F r_x = roughness * -1.0f + 1.0f, r_y = roughness * -0.0275f + 0.0425f;
  const F r_z = roughness * -0.572f + 1.04f, r_w = roughness * 0.022f - 0.04f;
  // 2^(-9.28 NdotV) as (e^-u)^16, e^-u by its Taylor series to u^4 (u <= 0.41: within 0.2%), in any lane type.
  const F u = n_dot_v * (9.28f * 0.693147f / 16.0f);
  F fade = 1.0f - u * (1.0f - u * (0.5f - u * (1.0f / 6.0f - u * (1.0f / 24.0f))));
  fade = fade * fade, fade = fade * fade, fade = fade * fade, fade = fade * fade;
  const F a004 = min(r_x * r_x, fade) * r_x + r_y;
  a = a004 * -1.04f + r_z;
  b = a004 * 1.04f + r_w;
}

// Khronos PBR Neutral tone mapping (Khronos, "PBR Neutral Tone Mapping", 2024).
template <class F>
FACET_LANES_INLINE Rgb<F> tone_map_neutral(Rgb<F> c) {
  constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f;
  const F x = min(c.r, min(c.g, c.b));
  const F offset = select(x < 0.08f, x - 6.25f * x * x, constant<F>(0.04f));
  c = {c.r - offset, c.g - offset, c.b - offset};
  const F peak = max(c.r, max(c.g, c.b));
  constexpr float d = 1.0f - kStart;
  const F new_peak = 1.0f - d * d / (peak + d - kStart);
  const F scale = new_peak / peak;
  const F g = 1.0f - 1.0f / (kDesaturation * (peak - new_peak) + 1.0f);
  const auto channel = [&](const F& v) {
    const F compressed = v * scale;
    return select(peak < kStart, v, compressed + (new_peak - compressed) * g);
  };
  return {channel(c.r), channel(c.g), channel(c.b)};
}

// ACES filmic: sRGB to the fit's input space, the RRT+ODT rational fit, back to sRGB, clamped.
template <class F>
FACET_LANES_INLINE Rgb<F> tone_map_aces(const Rgb<F>& c) {
  const F r = 0.59719f * c.r + 0.35458f * c.g + 0.04823f * c.b;
  const F g = 0.07600f * c.r + 0.90834f * c.g + 0.01566f * c.b;
  const F b = 0.02840f * c.r + 0.13383f * c.g + 0.83777f * c.b;
  const auto fit = [](const F& v) {
    const F num = v * (v + 0.0245786f) - 0.000090537f;
    const F den = v * (0.983729f * v + 0.4329510f) + 0.238081f;
    return num / den;
  };
  const F fr = fit(r), fg = fit(g), fb = fit(b);
  return {saturate(1.60475f * fr - 0.53108f * fg - 0.07367f * fb),
          saturate(-0.10208f * fr + 1.10813f * fg - 0.00605f * fb),
          saturate(-0.00327f * fr - 0.07276f * fg + 1.07602f * fb)};
}

// Exposure, then the tone curve; the result is linear in [0, 1], to be sRGB-encoded for display.
template <class F>
FACET_LANES_INLINE Rgb<F> tone_map(const Rgb<F>& c, ToneMapping mapping, float exposure) {
  switch (mapping) {
    case ToneMapping::neutral: return tone_map_neutral(c * constant<F>(exposure));
    case ToneMapping::aces: return tone_map_aces(c * constant<F>(exposure / 0.6f));
    case ToneMapping::none: break;
  }
  const Rgb<F> e = c * constant<F>(exposure);
  return {saturate(e.r), saturate(e.g), saturate(e.b)};
}

}  // namespace facet::brdf
