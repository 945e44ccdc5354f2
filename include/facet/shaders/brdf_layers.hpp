// brdf_layers.hpp - the layers over glTF's core BRDF: KHR_materials_clearcoat's coat and KHR_materials_sheen.
#pragma once

#include <cstdint>

#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"

namespace facet::brdf {

// 2^x and log2(x) from exact operations only (brdf.hpp's rule), to about 2e-6 relative: the sheen's power and
// exponential need them, and std::exp2 may round differently on another CPU or in the browser.
// (__builtin_bit_cast: the browser build's standard library has no std::bit_cast.)
inline float from_bits(std::int32_t bits) { return __builtin_bit_cast(float, bits); }
inline std::int32_t to_bits(float v) { return __builtin_bit_cast(std::int32_t, v); }
template <class L>
FACET_LANES_INLINE simd::FloatT<L> from_bits(const simd::IntT<L>& bits) {
  return simd::bit_cast<simd::FloatT<L>>(bits);
}
template <class L>
FACET_LANES_INLINE simd::IntT<L> to_bits(const simd::FloatT<L>& v) {
  return simd::bit_cast<simd::IntT<L>>(v);
}
inline std::int32_t to_int(float v) { return static_cast<std::int32_t>(v); }
template <class L>
FACET_LANES_INLINE simd::IntT<L> to_int(const simd::FloatT<L>& v) {
  return simd::truncate(v);
}

// 2^x = 2^i 2^f with i = floor(x) and f in [0, 1): 2^i built in the exponent's bits, 2^f by its Taylor series
// in f ln 2 (degree 7). x is clamped to [-126, 127], where both are normal floats.
template <class F>
FACET_LANES_INLINE F exp2(const F& x) {
  const F clamped = min(max(x, constant<F>(-126.0f)), constant<F>(127.0f));
  const F whole = floor(clamped);
  const F t = (clamped - whole) * 0.693147181f;
  F p = 1.0f + t * (1.0f / 7.0f);
  p = 1.0f + t * (1.0f / 6.0f) * p;
  p = 1.0f + t * (1.0f / 5.0f) * p;
  p = 1.0f + t * (1.0f / 4.0f) * p;
  p = 1.0f + t * (1.0f / 3.0f) * p;
  p = 1.0f + t * (1.0f / 2.0f) * p;
  p = 1.0f + t * p;
  return p * from_bits((to_int(whole) + 127) << 23);
}

// log2(x) for a normal x > 0: the exponent's bits, plus log2 of the mantissa m in [1, 2) by the series
// 2 atanh(s) / ln 2 with s = (m - 1) / (m + 1) < 1/3.
template <class F>
FACET_LANES_INLINE F log2(const F& x) {
  const auto bits = to_bits(x);
  const F exponent = [&] {
    if constexpr (std::is_same_v<F, float>) {
      return static_cast<float>(((bits >> 23) & 255) - 127);
    } else {
      return simd::to_float(((bits >> 23) & 255) - 127);
    }
  }();
  const F m = from_bits((bits & 0x007fffff) | 0x3f800000);
  const F s = (m - 1.0f) / (m + 1.0f);
  const F s2 = s * s;
  const F series = s * (1.0f + s2 * (1.0f / 3.0f + s2 * (1.0f / 5.0f + s2 * (1.0f / 7.0f + s2 * (1.0f / 9.0f)))));
  return exponent + series * 2.88539008f;  // 2 / ln 2
}

// The clear coat's Fresnel factor at normal incidence: a varnish of index of refraction 1.5 (the extension's).
inline constexpr float kCoatF0 = 0.04f;

// The coat's specular lobe for one light, f(l, v) |NdotL| with its own normal and roughness (the core BRDF's GGX
// lobe with f0 0.04 and f90 1); the light's colour is the caller's.
template <class F>
FACET_LANES_INLINE F reflect_coat(const F& n_dot_l, const F& n_dot_v, const F& n_dot_h, const F& v_dot_h,
                                  const F& alpha) {
  const F fresnel = kCoatF0 + (1.0f - kCoatF0) * schlick_weight(v_dot_h);
  return fresnel * distribution_ggx(n_dot_h, alpha) * visibility_smith_ggx(n_dot_l, n_dot_v, alpha) * n_dot_l;
}

// How much of the layers below the coat shows through: 1 - clearcoat Fresnel(NdotV of the coat's normal).
template <class F>
FACET_LANES_INLINE F coat_transmittance(const F& clearcoat, const F& n_dot_v) {
  return 1.0f - clearcoat * (kCoatF0 + (1.0f - kCoatF0) * schlick_weight(n_dot_v));
}

// The sheen's microfacet distribution, "Charlie" (Estevez and Kulla, "Production Friendly Microfacet Sheen BRDF",
// 2017), as KHR_materials_sheen defines it with alpha = sheenRoughness^2:
//   D = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi)
// sin^2 is kept above 2^-7, as three.js and Filament do, so that the power stays finite.
template <class F>
FACET_LANES_INLINE F distribution_charlie(const F& n_dot_h, const F& alpha) {
  const F inverse_alpha = 1.0f / alpha;
  const F sin2 = max(1.0f - n_dot_h * n_dot_h, constant<F>(0.0078125f));
  return (2.0f + inverse_alpha) * exp2(log2(sin2) * (0.5f * inverse_alpha)) * (1.0f / (2.0f * kPi));
}

// Neubelt and Pettineo's visibility for the sheen ("Crafting a Next-Gen Material Pipeline for The Order: 1886"):
//   V = 1 / (4 (NdotL + NdotV - NdotL NdotV)), at most 1.
template <class F>
FACET_LANES_INLINE F visibility_neubelt(const F& n_dot_l, const F& n_dot_v) {
  const F sum = n_dot_l + n_dot_v - n_dot_l * n_dot_v;
  return min(1.0f / max(4.0f * sum, constant<F>(1e-6f)), constant<F>(1.0f));
}

// The sheen lobe's directional albedo E(NdotV): the fraction of light it reflects, which the layers below lose.
// three.js's curve fit to Estevez and Kulla's table, so that both draw sheen alike:
//   E = exp(a NdotV + b), a and b polynomials in the roughness r and 1 / (r + 0.1).
template <class F>
FACET_LANES_INLINE F sheen_albedo(const F& n_dot_v, const F& roughness) {
  const F r2 = roughness * roughness;
  const F r_inverse = 1.0f / (roughness + 0.1f);
  const F a = -1.9362f + 1.0678f * roughness + 0.4573f * r2 - 0.8469f * r_inverse;
  const F b = -0.6014f + 0.5538f * roughness - 0.4670f * r2 - 0.1255f * r_inverse;
  return saturate(exp2((a * n_dot_v + b) * 1.44269504f));  // e^x = 2^(x log2 e)
}

// The sheen lobe for one light, f_sheen(l, v) |NdotL| per unit of sheen colour:
//   D_charlie V_neubelt |NdotL|
template <class F>
FACET_LANES_INLINE F reflect_sheen(const F& n_dot_l, const F& n_dot_v, const F& n_dot_h, const F& alpha) {
  return distribution_charlie(n_dot_h, alpha) * visibility_neubelt(n_dot_l, n_dot_v) * n_dot_l;
}

// The largest channel of a colour: how much the sheen takes from the layers below (the extension's max3).
template <class F>
FACET_LANES_INLINE F max3(const Rgb<F>& c) {
  return max(max(c.r, c.g), c.b);
}

}  // namespace facet::brdf
