// texture.hpp - RGBA8 textures with OpenGL-style sampling (nearest, bilinear, trilinear), wrap modes and mipmaps.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "facet/detail/bits.hpp"
#include "facet/detail/texel_math.hpp"
#include "facet/framebuffer.hpp"
#include "facet/sampler.hpp"
#include "facet/simd.hpp"

namespace facet {

inline constexpr int kMaxTextureSize = 16384;  // texels per side; 2^14, so at most 15 mip levels
inline constexpr int kMaxTextureLevels = 15;


// What a texture's red, green and blue bytes hold (alpha is always linear coverage).
enum class TexelEncoding {
  linear,  // values filtered as stored: data such as normal maps, and the benchmark's checker
  // sRGB-encoded colour, as image files and glTF base colour textures hold it: decoded to linear light before
  // filtering (bilinear, trilinear and the mipmap chain) and the filtered colour encoded again, since facet shades
  // and writes sRGB-encoded colours, as OpenGL does with sRGB textures and no sRGB framebuffer
  srgb,
};

class Texture {
 public:
  Texture() = default;
  // rgba holds width*height little-endian RGBA8 texels (r in the low byte), row 0 at v = 0, column 0 at u = 0.
  // Throws std::invalid_argument unless 1 <= width, height <= kMaxTextureSize and the size matches.
  Texture(int width, int height, std::vector<std::uint32_t> rgba, TexelEncoding encoding = TexelEncoding::linear);

  int width() const { return levels_[0].width; }
  int height() const { return levels_[0].height; }
  int levels() const { return level_count_; }  // 1 until generate_mipmaps(), 0 when empty
  bool empty() const { return level_count_ == 0; }
  TexelEncoding encoding() const { return srgb_ ? TexelEncoding::srgb : TexelEncoding::linear; }
  int level_width(int level) const { return levels_[static_cast<std::size_t>(level)].width; }
  int level_height(int level) const { return levels_[static_cast<std::size_t>(level)].height; }

  // Builds the full chain down to 1x1; each level is max(1, floor(previous / 2)) per side, as in OpenGL, and each
  // texel is the area-weighted average of the texels of the previous level it covers (a 2x2 box for even sizes).
  void generate_mipmaps();

  // Texel (x, y) of a level as floats in [0, 1], as stored (sRGB-encoded for an sRGB texture); no wrapping, the
  // indices must be in range.
  glm::vec4 texel(int level, int x, int y) const;

  // Level 0 only: nearest or bilinear (trilinear has no derivatives here, so it behaves like bilinear).
  glm::vec4 sample(glm::vec2 uv, const Sampler& sampler) const {
    // The benchmark's case (bilinear, repeat, power-of-two size) stays inline and branch-light.
    if (bilinear_repeat_pow2_applies(sampler)) return bilinear_repeat_pow2(uv);
    return sample_level0(uv, sampler);
  }

  // With the uv derivatives across one pixel in x and y: trilinear picks the level of detail
  // lod = log2(max(|duv_dx * size|, |duv_dy * size|)) and blends the two nearest levels; lod <= 0 (magnification)
  // samples level 0 bilinearly. nearest and bilinear ignore the derivatives, as in OpenGL.
  glm::vec4 sample(glm::vec2 uv, glm::vec2 duv_dx, glm::vec2 duv_dy, const Sampler& sampler) const;

  // sample(uv, duv_dx, duv_dy, sampler) in linear light: an sRGB texture's filtered colour is returned decoded
  // rather than encoded again (a linear texture's as sample() gives it), for shading in linear light.
  glm::vec4 sample_linear(glm::vec2 uv, glm::vec2 duv_dx, glm::vec2 duv_dy, const Sampler& sampler) const;

  // sample(uv, sampler) for 16 lanes of any layout. The benchmark's case (bilinear, repeat, power-of-two) runs in
  // lanes with the same IEEE operations as the scalar path, so both give identical results, for both encodings;
  // other samplers sample lane by lane.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> sample_lanes(const simd::Vec2T<L>& uv, const Sampler& sampler) const;

  // sample_linear for 16 lanes of any layout, with each lane's derivatives. The common case of colour maps (sRGB,
  // trilinear, repeat, power-of-two) runs in lanes with the same IEEE operations as the scalar path (log2 taken
  // lane by lane, as the scalar path takes it), so both give identical results; other textures sample lane by lane,
  // only the lanes set in `lanes` (the pixels a shader call colours; the others come out 0).
  static constexpr unsigned kAllLanes = (1u << simd::kLanes) - 1u;
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> sample_linear_lanes(const simd::Vec2T<L>& uv, const simd::Vec2T<L>& duv_dx,
                                                         const simd::Vec2T<L>& duv_dy, const Sampler& sampler,
                                                         unsigned lanes = kAllLanes) const;

  // Starts loading the texels sample_lanes(uv, sampler) will read, without waiting for them: call it early enough
  // and the samples find them in cache. Only the benchmark's case (bilinear, repeat, power-of-two) prefetches.
  template <class L>
  FACET_LANES_INLINE void prefetch_lanes(const simd::Vec2T<L>& uv, const Sampler& sampler) const;

 private:
  // Each level is stored with one extra column and one extra row, copies of column 0 and row 0: with repeat
  // wrapping the texel right of (or above) the last one is then simply the next in memory, so the hot path reads
  // each pair of neighbours with one 8-byte load. Other wrap modes index explicitly and never read the padding.
  struct Level {
    int width = 0, height = 0;
    int stride = 0;                       // texels per stored row: width + 1, padded (row_stride)
    float fwidth = 0.0f, fheight = 0.0f;  // the size as floats, so sampling does not convert per call
    std::size_t offset = 0;               // of texel (0, 0) in texels_
  };

  // BENCHMARK.md section 7: s = u*W - 0.5, i = floor(s), alpha = s - i, indices wrapped by a mask; thanks to the
  // padding, texels i+1 and j+1 are the next ones in memory even at the last column and row.
  glm::vec4 bilinear_repeat_pow2(glm::vec2 uv) const {
    const Level& l = levels_[0];
    const detail::Split p = detail::split_floor(uv.x * l.fwidth - 0.5f, uv.y * l.fheight - 0.5f);
    const std::uint32_t* t00 =
        texels_.data() + static_cast<std::size_t>(p.j & (l.height - 1)) * l.stride + (p.i & (l.width - 1));
    std::uint64_t bottom, top;
    std::memcpy(&bottom, t00, sizeof bottom);
    std::memcpy(&top, t00 + l.stride, sizeof top);
    if constexpr (!detail::kLittleEndian) {  // keep the left texel in the low half
      bottom = bottom << 32 | bottom >> 32;
      top = top << 32 | top >> 32;
    }
    return srgb_ ? detail::blend_srgb(bottom, top, p.alpha, p.beta) : detail::blend(bottom, top, p.alpha, p.beta);
  }

  template <bool Srgb, class L>
  FACET_LANES_INLINE simd::ColorT<L> bilinear_repeat_pow2_lanes(const simd::Vec2T<L>& uv) const;
  // sample_linear's levels of detail and its bilinear lookups in linear light, for an sRGB texture with mipmaps
  // sampled trilinearly with repeat wrapping at power-of-two sizes.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> trilinear_srgb_lanes(const simd::Vec2T<L>& uv, const simd::Vec2T<L>& duv_dx,
                                                          const simd::Vec2T<L>& duv_dy) const;
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> bilinear_srgb_lanes(const simd::Vec2T<L>& uv, const simd::IntT<L>& level) const;
  bool trilinear_srgb_lanes_apply(const Sampler& sampler) const {
    return srgb_ && pow2_ && level_count_ > 1 && sampler.filter == Filter::trilinear &&
           sampler.wrap_u == Wrap::repeat && sampler.wrap_v == Wrap::repeat;
  }
  bool bilinear_repeat_pow2_applies(const Sampler& sampler) const {
    return pow2_ && sampler.filter != Filter::nearest && sampler.wrap_u == Wrap::repeat &&
           sampler.wrap_v == Wrap::repeat;
  }
  // Per lane, the offset of the bottom-left texel of the bilinear footprint and the weights (split_floor's).
  template <class L>
  FACET_LANES_INLINE simd::IntT<L> bilinear_repeat_pow2_first(const simd::Vec2T<L>& uv, simd::FloatT<L>& alpha,
                                                              simd::FloatT<L>& beta) const;
  // Texel coordinates limited to +-2^30, NaN to the lower limit (as maxps does in split_floor), so that their
  // conversion to integers is defined for any uv.
  template <class L>
  FACET_LANES_INLINE static simd::FloatT<L> clamp_texel_coordinate(simd::FloatT<L> v);
  // Texel coordinates v split into their floor, as an int, and the fraction above it, per lane.
  template <class L>
  FACET_LANES_INLINE static void split_lanes(simd::FloatT<L> v, simd::IntT<L>& index, simd::FloatT<L>& fraction);

  // The colours of the lanes set in `lanes` from sample(k), one scalar sample per lane; the others 0.
  template <class L, class Sample>
  FACET_LANES_INLINE static simd::ColorT<L> lane_by_lane(Sample&& sample, unsigned lanes) {
    simd::ColorT<L> c{};
    for (unsigned left = lanes & kAllLanes; left; left &= left - 1) {
      const int k = std::countr_zero(left);
      const glm::vec4 s = sample(k);
      c.r[k] = s.r, c.g[k] = s.g, c.b[k] = s.b, c.a[k] = s.a;
    }
    return c;
  }

  void pad_level(int level);  // fills the extra column and row of a level from column 0 and row 0
  glm::vec4 sample_level0(glm::vec2 uv, const Sampler& sampler) const;
  glm::vec4 sample_nearest(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const;
  glm::vec4 sample_bilinear(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const;
  // sample_bilinear's result in linear light (an sRGB texture's colour decoded, not encoded again), for trilinear's
  // blend between levels.
  glm::vec4 sample_bilinear_linear(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const;

  std::array<Level, kMaxTextureLevels> levels_{};
  int level_count_ = 0;
  bool pow2_ = false;                  // level 0 has power-of-two sides: the inline fast path applies
  bool srgb_ = false;                  // TexelEncoding::srgb
  // All levels, level 0 first, each padded and row-major, row 0 at v = 0.
  std::vector<std::uint32_t, CacheAlignedAllocator<std::uint32_t>> texels_;
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

template <class L>
inline simd::ColorT<L> Texture::sample_lanes(const simd::Vec2T<L>& uv, const Sampler& sampler) const {
  if (bilinear_repeat_pow2_applies(sampler))
    return srgb_ ? bilinear_repeat_pow2_lanes<true>(uv) : bilinear_repeat_pow2_lanes<false>(uv);
  return lane_by_lane<L>(
      [&](int k) __attribute__((always_inline)) { return sample(glm::vec2(uv.x[k], uv.y[k]), sampler); }, kAllLanes);
}

template <class L>
inline simd::ColorT<L> Texture::sample_linear_lanes(const simd::Vec2T<L>& uv, const simd::Vec2T<L>& duv_dx,
                                                    const simd::Vec2T<L>& duv_dy, const Sampler& sampler,
                                                    unsigned lanes) const {
  if (trilinear_srgb_lanes_apply(sampler)) return trilinear_srgb_lanes(uv, duv_dx, duv_dy);
  return lane_by_lane<L>(
      [&](int k) __attribute__((always_inline)) {
        return sample_linear(glm::vec2(uv.x[k], uv.y[k]), glm::vec2(duv_dx.x[k], duv_dx.y[k]),
                             glm::vec2(duv_dy.x[k], duv_dy.y[k]), sampler);
      },
      lanes);
}

// sample_linear's trilinear path lane by lane: lod = log2 of the longer pixel step in level-0 texels; level 0 where
// lod <= 0 (or NaN), the last level where lod reaches it, otherwise the two levels around lod blended by its
// fraction (a + (b - a) * f, which is a itself where f is 0).
template <class L>
inline simd::ColorT<L> Texture::trilinear_srgb_lanes(const simd::Vec2T<L>& uv, const simd::Vec2T<L>& duv_dx,
                                                     const simd::Vec2T<L>& duv_dy) const {
  using namespace simd;
  using Float = FloatT<L>;
  using Int = IntT<L>;
  const float width = levels_[0].fwidth, height = levels_[0].fheight;
  // glm::length(d * size): the square root of x * x + y * y; std::max(a, b): a < b ? b : a.
  const Float sx = duv_dx.x * width, sy = duv_dx.y * height, tx = duv_dy.x * width, ty = duv_dy.y * height;
  const Float along_x = simd::sqrt(Float(sx * sx + sy * sy)), along_y = simd::sqrt(Float(tx * tx + ty * ty));
  const Float rho = select(along_x < along_y, along_y, along_x);
  Float lod;
  for (int k = 0; k < kLanes; ++k) lod[k] = std::log2(rho[k]);
  const Float last = splat<L>(static_cast<float>(level_count_ - 1)), zero = splat<L>(0.0f);
  const Float clamped = select(lod > 0.0f, select(lod < last, lod, last), zero);  // NaN to level 0
  const Int level = truncate(clamped);
  const Float f = select(lod < last, Float(clamped - to_float(level)), zero);
  const Int next = blend(level < level_count_ - 1, Int(level + 1), level);
  const ColorT<L> a = bilinear_srgb_lanes(uv, level), b = bilinear_srgb_lanes(uv, next);
  return {a.r + (b.r - a.r) * f, a.g + (b.g - a.g) * f, a.b + (b.b - a.b) * f, a.a + (b.a - a.a) * f};
}

// sample_bilinear_linear at each lane's level, with repeat wrapping at power-of-two sizes: split_floor, the four
// texels, red, green and blue decoded by table and alpha / 255, then glm::mix's x * (1 - a) + y * a along u and v.
template <class L>
inline simd::ColorT<L> Texture::bilinear_srgb_lanes(const simd::Vec2T<L>& uv, const simd::IntT<L>& level) const {
  using namespace simd;
  using Float = FloatT<L>;
  using Int = IntT<L>;
  Float fwidth, fheight;
  Int wmask, hmask, stride, offset;
  for (int k = 0; k < kLanes; ++k) {
    const Level& l = levels_[static_cast<std::size_t>(level[k])];
    fwidth[k] = l.fwidth, fheight[k] = l.fheight;
    wmask[k] = l.width - 1, hmask[k] = l.height - 1;
    stride[k] = l.stride, offset[k] = static_cast<int>(l.offset);
  }
  Int i, j;
  Float alpha, beta;
  split_lanes(Float(uv.x * fwidth - 0.5f), i, alpha);
  split_lanes(Float(uv.y * fheight - 0.5f), j, beta);
  const Int i0 = i & wmask, i1 = Int(i + 1) & wmask;
  const Int row0 = offset + (j & hmask) * stride, row1 = offset + (Int(j + 1) & hmask) * stride;
  const Int at[4] = {row0 + i0, row0 + i1, row1 + i0, row1 + i1};
  const float* decode = detail::srgb_decode_table();
  Float c[4][4];  // [texel: 00, 10, 01, 11][channel]
  for (int t = 0; t < 4; ++t)
    for (int k = 0; k < kLanes; ++k) {
      const std::uint32_t texel = texels_[static_cast<std::size_t>(at[t][k])];
      c[t][0][k] = decode[texel & 0xffu];
      c[t][1][k] = decode[(texel >> 8) & 0xffu];
      c[t][2][k] = decode[(texel >> 16) & 0xffu];
      c[t][3][k] = static_cast<float>(texel >> 24) / 255.0f;
    }
  const Float keep_u = 1.0f - alpha, keep_v = 1.0f - beta;
  Float out[4];
  for (int ch = 0; ch < 4; ++ch) {
    const Float bottom = c[0][ch] * keep_u + c[1][ch] * alpha;
    const Float top = c[2][ch] * keep_u + c[3][ch] * alpha;
    out[ch] = bottom * keep_v + top * beta;
  }
  return {out[0], out[1], out[2], out[3]};
}

// split_floor's values for lanes: within the clamp's +-2^30, floor(v) converts to an int exactly. One rounding
// instruction instead of a truncation corrected by one where it rounded up (a compare and a masked add).
template <class L>
inline void Texture::split_lanes(simd::FloatT<L> v, simd::IntT<L>& index, simd::FloatT<L>& fraction) {
  v = clamp_texel_coordinate(v);
  const simd::FloatT<L> lower = simd::floor(v);
  index = simd::truncate(lower);
  fraction = v - lower;
}

template <class L>
inline simd::FloatT<L> Texture::clamp_texel_coordinate(simd::FloatT<L> v) {
  using namespace simd;
  constexpr float lo = -detail::kTexelCoordinateLimit, hi = detail::kTexelCoordinateLimit;
  v = select(v > lo, v, splat<L>(lo));
  return select(v < hi, v, splat<L>(hi));
}

template <class L>
inline simd::IntT<L> Texture::bilinear_repeat_pow2_first(const simd::Vec2T<L>& uv, simd::FloatT<L>& alpha,
                                                         simd::FloatT<L>& beta) const {
  using namespace simd;
  using Float = FloatT<L>;
  using Int = IntT<L>;
  const Level& l = levels_[0];
  Int i, j;
  split_lanes(Float(uv.x * l.fwidth - 0.5f), i, alpha);
  split_lanes(Float(uv.y * l.fheight - 0.5f), j, beta);
  return (j & (l.height - 1)) * l.stride + (i & (l.width - 1));
}

template <class L>
inline void Texture::prefetch_lanes(const simd::Vec2T<L>& uv, const Sampler& sampler) const {
  using namespace simd;
  using Float = FloatT<L>;
  using Int = IntT<L>;
  if (!bilinear_repeat_pow2_applies(sampler)) return;
  // A prefetch needs the line, not the texel: truncation instead of split_floor's floor and weights, which is the
  // same index for s >= 0 and one texel off below it.
  const Level& l = levels_[0];
  const auto index = [](Float s, int size) __attribute__((always_inline)) {
    return truncate(clamp_texel_coordinate(s)) & (size - 1);
  };
  const Int first = index(uv.y * l.fheight - 0.5f, l.height) * l.stride + index(uv.x * l.fwidth - 0.5f, l.width);
  const std::uint32_t* texels = texels_.data();
  for (int k = 0; k < simd::kLanes; ++k) {
    __builtin_prefetch(texels + first[k]);
    __builtin_prefetch(texels + first[k] + levels_[0].stride);
  }
}

// bilinear_repeat_pow2 lane by lane: split_floor, the padded 8-byte pair loads and blend (or blend_srgb), in the
// same order.
template <bool Srgb, class L>
inline simd::ColorT<L> Texture::bilinear_repeat_pow2_lanes(const simd::Vec2T<L>& uv) const {
  using namespace simd;
  using Float = FloatT<L>;
  using Int = IntT<L>;
  using UInt = UIntT<L>;
  const Level& l = levels_[0];
  Float alpha, beta;
  const Int first = bilinear_repeat_pow2_first(uv, alpha, beta);
  // The texel pairs are gathered with one 8-byte load each through memory, then split into left and right texels
  // with two shuffles: inserting 64 texels lane by lane would chain 64 dependent instructions.
  alignas(64) std::uint64_t bottom[kLanes], top[kLanes];
  const std::uint32_t* texels = texels_.data();
  for (int k = 0; k < kLanes; ++k) {
    std::memcpy(&bottom[k], texels + first[k], sizeof bottom[k]);
    std::memcpy(&top[k], texels + first[k] + l.stride, sizeof top[k]);
  }
  const UInt b0 = load<UInt>(bottom), b1 = load<UInt>(bottom + kLanes / 2);
  const UInt u0 = load<UInt>(top), u1 = load<UInt>(top + kLanes / 2);
  // On a little-endian machine the left texel of each pair is the lower 32 bits, i.e. the even lane.
  constexpr int kLeft = detail::kLittleEndian ? 0 : 1, kRight = 1 - kLeft;
  const UInt t00 = deinterleave<kLeft>(b0, b1), t10 = deinterleave<kRight>(b0, b1);
  const UInt t01 = deinterleave<kLeft>(u0, u1), t11 = deinterleave<kRight>(u0, u1);
  auto channel = [&](int shift) __attribute__((always_inline)) {
    auto bytes = [&](UInt t) __attribute__((always_inline)) {
      return to_float(to_int((t >> shift) & 0xffu));
    };
    const Float c00 = bytes(t00), c10 = bytes(t10), c01 = bytes(t01), c11 = bytes(t11);
    const Float bottom = c00 + (c10 - c00) * alpha;
    const Float top = c01 + (c11 - c01) * alpha;
    return (bottom + (top - bottom) * beta) / 255.0f;
  };
  if constexpr (Srgb) {
    // blend_srgb per lane: a table lookup per texel and channel, which no lane instruction does faster.
    const float* decode = detail::srgb_decode_table();
    const float* encode = detail::srgb_encode_table();
    auto colour = [&](int shift) __attribute__((always_inline)) {
      Float c00, c10, c01, c11;
      for (int k = 0; k < kLanes; ++k) {
        c00[k] = decode[(t00[k] >> shift) & 0xffu];
        c10[k] = decode[(t10[k] >> shift) & 0xffu];
        c01[k] = decode[(t01[k] >> shift) & 0xffu];
        c11[k] = decode[(t11[k] >> shift) & 0xffu];
      }
      const Float bottom = c00 + (c10 - c00) * alpha;
      const Float top = c01 + (c11 - c01) * alpha;
      const Float mixed = bottom + (top - bottom) * beta;
      Float out;
      for (int k = 0; k < kLanes; ++k) out[k] = detail::srgb_encode(mixed[k], encode);
      return out;
    };
    return {colour(0), colour(8), colour(16), channel(24)};
  }
  return {channel(0), channel(8), channel(16), channel(24)};
}

#pragma GCC diagnostic pop

// Loads a PNG, JPEG, TGA or BMP file as RGBA (missing channels filled as stb_image does: grey to RGB, alpha 255),
// flipped so that row 0 (the image's bottom row) is at v = 0, with mipmaps. Image files hold sRGB colour unless
// they hold data (a normal map: TexelEncoding::linear). Throws InputError naming the file.
Texture load_texture(const std::filesystem::path& path, TexelEncoding encoding = TexelEncoding::srgb);

// The benchmark texture of BENCHMARK.md section 7 (size x size, 128-texel cells, row 0 at v = 0), without mipmaps
// (the benchmark samples with GL_LINEAR). Throws std::invalid_argument unless 1 <= size <= kMaxTextureSize.
Texture make_checker_texture(int size = 1024);

}  // namespace facet
