// texel_math.hpp - the arithmetic of texture sampling: texel indices and weights, the bilinear blend, sRGB curves.
#pragma once

#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

#include "facet/detail/bits.hpp"

// x86-64 samples with SSE2 (every x86-64 CPU has it); elsewhere, the portable functions below, which it must match.
#if defined(__SSE2__) && defined(__x86_64__)
#define FACET_TEXTURE_SSE2 1
#include <emmintrin.h>
#endif

namespace facet {
namespace detail {

// For s and t: floor as an int and the fraction s - floor(s), the texel index and weight of the bilinear formula.
// The clamp keeps the conversion defined for huge, infinite or NaN coordinates (NaN goes to -2^30 with weight 0);
// +-2^30 are multiples of every power-of-two size, so repeat wrapping of large values is unaffected. Exact: a
// non-integer float is below 2^23 in magnitude, where i - 1 and float(i) are exact.
struct Split {
  int i, j;
  float alpha, beta;
};
inline constexpr float kTexelCoordinateLimit = 1073741824.0f;  // 2^30

inline Split split_floor_portable(float s, float t) {
  constexpr float lo = -kTexelCoordinateLimit, hi = kTexelCoordinateLimit;
  auto one = [](float v, float& fraction) {
    v = lo < v ? v : lo;
    v = v < hi ? v : hi;
    int i = static_cast<int>(v);
    i -= v < static_cast<float>(i) ? 1 : 0;
    fraction = v - static_cast<float>(i);
    return i;
  };
  Split r{};
  r.i = one(s, r.alpha);
  r.j = one(t, r.beta);
  return r;
}

// A texel's channels as floats in 0..255: the bilinear formula interpolates these and divides by 255 last.
inline glm::vec4 unpack_bytes(std::uint32_t p) {
  return glm::vec4(static_cast<float>(p & 0xffu), static_cast<float>((p >> 8) & 0xffu),
                   static_cast<float>((p >> 16) & 0xffu), static_cast<float>(p >> 24));
}

// lerp(lerp(T00, T10, alpha), lerp(T01, T11, alpha), beta) / 255 with lerp(a, b, w) = a + (b - a) * w, given the
// pairs (T00 | T10 << 32) and (T01 | T11 << 32).
inline glm::vec4 blend_portable(std::uint64_t bottom_pair, std::uint64_t top_pair, float alpha, float beta) {
  const glm::vec4 t00 = unpack_bytes(static_cast<std::uint32_t>(bottom_pair));
  const glm::vec4 t10 = unpack_bytes(static_cast<std::uint32_t>(bottom_pair >> 32));
  const glm::vec4 t01 = unpack_bytes(static_cast<std::uint32_t>(top_pair));
  const glm::vec4 t11 = unpack_bytes(static_cast<std::uint32_t>(top_pair >> 32));
  const glm::vec4 bottom = t00 + (t10 - t00) * alpha;
  const glm::vec4 top = t01 + (t11 - t01) * alpha;
  return (bottom + (top - bottom) * beta) / 255.0f;
}

// sRGB's transfer functions (IEC 61966-2-1) by table, for textures whose texels are sRGB-encoded colour. The decode
// table maps a byte to linear light in [0, 1]; the encode table holds the exact curve at kSrgbEncodeSteps + 1 evenly
// spaced points of [0, 1], interpolated linearly by srgb_encode (off the curve by less than 2e-5).
inline constexpr int kSrgbEncodeSteps = 4096;
const float* srgb_decode_table();  // 256 entries
const float* srgb_encode_table();  // kSrgbEncodeSteps + 1 entries
// The decoding curve at kSrgbEncodeSteps + 1 evenly spaced points of [0, 1], for encoded values that are not bytes
// (a filtered texel, an interpolated vertex colour); interpolated linearly by srgb_decode (off by less than 3e-5).
const float* srgb_decode_curve_table();

// Linear light to its sRGB encoding, both in [0, 1]; values outside (and NaN) are clamped first.
inline float srgb_encode(float linear, const float* table) {
  const float x = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
  const float f = x * static_cast<float>(kSrgbEncodeSteps);
  int i = static_cast<int>(f);
  i = i < kSrgbEncodeSteps ? i : kSrgbEncodeSteps - 1;
  const float w = f - static_cast<float>(i);
  return table[i] + (table[i + 1] - table[i]) * w;
}

// An sRGB-encoded value in [0, 1] to linear light; values outside (and NaN) are clamped first.
inline float srgb_decode(float encoded, const float* table) { return srgb_encode(encoded, table); }

// blend for sRGB-encoded texels: red, green and blue decoded to linear light, interpolated there (the same lerps as
// blend) and encoded again; alpha, which is linear, exactly as blend does it.
inline glm::vec4 blend_srgb(std::uint64_t bottom_pair, std::uint64_t top_pair, float alpha, float beta) {
  const float* decode = srgb_decode_table();
  const float* encode = srgb_encode_table();
  const std::uint32_t t[4] = {static_cast<std::uint32_t>(bottom_pair), static_cast<std::uint32_t>(bottom_pair >> 32),
                              static_cast<std::uint32_t>(top_pair), static_cast<std::uint32_t>(top_pair >> 32)};
  glm::vec4 out;
  for (int c = 0; c < 4; ++c) {
    const auto value = [&](std::uint32_t texel) {
      const std::uint32_t byte = (texel >> (8 * c)) & 0xffu;
      return c < 3 ? decode[byte] : static_cast<float>(byte);
    };
    const float c00 = value(t[0]), c10 = value(t[1]), c01 = value(t[2]), c11 = value(t[3]);
    const float bottom = c00 + (c10 - c00) * alpha;
    const float top = c01 + (c11 - c01) * alpha;
    const float mixed = bottom + (top - bottom) * beta;
    out[c] = c < 3 ? srgb_encode(mixed, encode) : mixed / 255.0f;
  }
  return out;
}

// The same two functions in SSE2, for the scalar sampling path's per-pixel work: the same IEEE operations per
// lane, so they agree bit for bit with the portable ones (tests/unit/test_texture.cpp checks that).
#if defined(FACET_TEXTURE_SSE2)
inline Split split_floor_sse2(float s, float t) {
  __m128 st = _mm_setr_ps(s, t, 0.0f, 0.0f);
  st = _mm_min_ps(_mm_max_ps(st, _mm_set1_ps(-kTexelCoordinateLimit)), _mm_set1_ps(kTexelCoordinateLimit));
  __m128i ij = _mm_cvttps_epi32(st);                                                // truncates toward zero
  ij = _mm_add_epi32(ij, _mm_castps_si128(_mm_cmplt_ps(st, _mm_cvtepi32_ps(ij))));  // -1 where that rounded up
  const __m128 fraction = _mm_sub_ps(st, _mm_cvtepi32_ps(ij));
  return Split{_mm_cvtsi128_si32(ij), _mm_cvtsi128_si32(_mm_shuffle_epi32(ij, 1)), _mm_cvtss_f32(fraction),
               _mm_cvtss_f32(_mm_shuffle_ps(fraction, fraction, 1))};
}

inline glm::vec4 blend_sse2(std::uint64_t bottom_pair, std::uint64_t top_pair, float alpha, float beta) {
  const __m128i zero = _mm_setzero_si128();
  // bytes -> 16-bit -> 32-bit lanes, one texel per half of the 16-bit vector.
  const __m128i b16 = _mm_unpacklo_epi8(_mm_cvtsi64_si128(static_cast<long long>(bottom_pair)), zero);
  const __m128i t16 = _mm_unpacklo_epi8(_mm_cvtsi64_si128(static_cast<long long>(top_pair)), zero);
  const __m128 t00 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(b16, zero));
  const __m128 t10 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(b16, zero));
  const __m128 t01 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(t16, zero));
  const __m128 t11 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(t16, zero));
  const __m128 a = _mm_set1_ps(alpha);
  const __m128 bottom = _mm_add_ps(t00, _mm_mul_ps(_mm_sub_ps(t10, t00), a));
  const __m128 top = _mm_add_ps(t01, _mm_mul_ps(_mm_sub_ps(t11, t01), a));
  const __m128 mixed = _mm_add_ps(bottom, _mm_mul_ps(_mm_sub_ps(top, bottom), _mm_set1_ps(beta)));
  glm::vec4 result;
  _mm_storeu_ps(&result.x, _mm_div_ps(mixed, _mm_set1_ps(255.0f)));
  return result;
}

inline Split split_floor(float s, float t) { return split_floor_sse2(s, t); }
inline glm::vec4 blend(std::uint64_t bottom, std::uint64_t top, float alpha, float beta) {
  return blend_sse2(bottom, top, alpha, beta);
}
#else
inline Split split_floor(float s, float t) { return split_floor_portable(s, t); }
inline glm::vec4 blend(std::uint64_t bottom, std::uint64_t top, float alpha, float beta) {
  return blend_portable(bottom, top, alpha, beta);
}
#endif

}  // namespace detail

}  // namespace facet
