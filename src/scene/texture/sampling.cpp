// sampling.cpp - the general texture sampling paths: every wrap mode, any size, nearest and trilinear filtering.
#include <algorithm>
#include <cmath>

#include "facet/texture.hpp"

namespace facet {

namespace {

// Wraps a texel index into 0..n-1 as OpenGL does (GL 4.6 table 8.20), applied to integer indices for both nearest
// and linear filtering.
inline int wrap_index(int i, int n, Wrap wrap) {
  switch (wrap) {
    case Wrap::repeat: {
      if ((n & (n - 1)) == 0) return i & (n - 1);  // every level of a power-of-two texture: no division
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
    case Wrap::clamp: return std::clamp(i, 0, n - 1);
    case Wrap::mirror: {
      // Period 2n: the first n texels forward, the next n backward.
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
  }
  return 0;
}

// The four texels of a level's bilinear footprint around uv, wrapped, and their weights (split_floor's).
struct Footprint {
  std::uint32_t t00, t10, t01, t11;  // bottom-left, bottom-right, top-left, top-right
  float alpha, beta;
};

// Takes the level by deduced type: Texture::Level is private, and only its members call this.
template <class Level>
Footprint bilinear_footprint(const Level& l, const std::uint32_t* texels, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) {
  const detail::Split p = detail::split_floor(uv.x * l.fwidth - 0.5f, uv.y * l.fheight - 0.5f);
  const int i0 = wrap_index(p.i, l.width, wrap_u), i1 = wrap_index(p.i + 1, l.width, wrap_u);
  const int j0 = wrap_index(p.j, l.height, wrap_v), j1 = wrap_index(p.j + 1, l.height, wrap_v);
  const std::uint32_t* row0 = texels + l.offset + static_cast<std::size_t>(j0) * l.stride;
  const std::uint32_t* row1 = texels + l.offset + static_cast<std::size_t>(j1) * l.stride;
  return {row0[i0], row0[i1], row1[i0], row1[i1], p.alpha, p.beta};
}

}  // namespace

glm::vec4 Texture::sample_level0(glm::vec2 uv, const Sampler& sampler) const {
  if (empty()) return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);  // what OpenGL returns for an incomplete texture
  if (sampler.filter == Filter::nearest) return sample_nearest(0, uv, sampler.wrap_u, sampler.wrap_v);
  return sample_bilinear(0, uv, sampler.wrap_u, sampler.wrap_v);
}

glm::vec4 Texture::sample_nearest(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const {
  const Level& l = levels_[static_cast<std::size_t>(level)];
  const detail::Split p = detail::split_floor(uv.x * l.fwidth, uv.y * l.fheight);
  const int i = wrap_index(p.i, l.width, wrap_u), j = wrap_index(p.j, l.height, wrap_v);
  return detail::unpack_bytes(texels_[l.offset + static_cast<std::size_t>(j) * l.stride + i]) / 255.0f;
}

// The same arithmetic as bilinear_repeat_pow2 (BENCHMARK.md section 7), with general wrapping.
glm::vec4 Texture::sample_bilinear(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const {
  const Footprint f = bilinear_footprint(levels_[static_cast<std::size_t>(level)], texels_.data(), uv, wrap_u, wrap_v);
  const std::uint64_t bottom = f.t00 | std::uint64_t{f.t10} << 32, top = f.t01 | std::uint64_t{f.t11} << 32;
  return srgb_ ? detail::blend_srgb(bottom, top, f.alpha, f.beta) : detail::blend(bottom, top, f.alpha, f.beta);
}

glm::vec4 Texture::sample_bilinear_linear(int level, glm::vec2 uv, Wrap wrap_u, Wrap wrap_v) const {
  const Footprint f = bilinear_footprint(levels_[static_cast<std::size_t>(level)], texels_.data(), uv, wrap_u, wrap_v);
  const float* decode = detail::srgb_decode_table();
  const auto value = [&](std::uint32_t texel) {
    const glm::vec4 v = detail::unpack_bytes(texel) / 255.0f;
    if (!srgb_) return v;
    const auto byte = [&](int c) { return decode[(texel >> (8 * c)) & 0xffu]; };
    return glm::vec4(byte(0), byte(1), byte(2), v.a);
  };
  const glm::vec4 bottom = glm::mix(value(f.t00), value(f.t10), f.alpha);
  const glm::vec4 top = glm::mix(value(f.t01), value(f.t11), f.alpha);
  return glm::mix(bottom, top, f.beta);
}

glm::vec4 Texture::sample(glm::vec2 uv, glm::vec2 duv_dx, glm::vec2 duv_dy, const Sampler& sampler) const {
  // GL_NEAREST and GL_LINEAR never use mipmaps; without a chain trilinear has only level 0 to use.
  if (sampler.filter != Filter::trilinear || level_count_ <= 1) return sample(uv, sampler);

  // OpenGL's scale factor rho: the longer of the two pixel steps, measured in level-0 texels.
  const glm::vec2 size(levels_[0].fwidth, levels_[0].fheight);
  const float rho = std::max(glm::length(duv_dx * size), glm::length(duv_dy * size));
  float lod = std::log2(rho);
  // Magnification (GL_LINEAR, threshold 0 for this filter pair), zero derivatives (-inf) and NaN all go to level 0.
  if (!(lod > 0.0f)) return sample(uv, sampler);

  const float max_level = static_cast<float>(level_count_ - 1);
  if (lod >= max_level) return sample_bilinear(level_count_ - 1, uv, sampler.wrap_u, sampler.wrap_v);
  const int d = static_cast<int>(lod);
  const float f = lod - static_cast<float>(d);
  if (f == 0.0f) return sample_bilinear(d, uv, sampler.wrap_u, sampler.wrap_v);
  if (!srgb_) {
    const glm::vec4 a = sample_bilinear(d, uv, sampler.wrap_u, sampler.wrap_v);
    const glm::vec4 b = sample_bilinear(d + 1, uv, sampler.wrap_u, sampler.wrap_v);
    return a + (b - a) * f;
  }
  // The two levels blend in linear light too; the colour is encoded once, at the end.
  const glm::vec4 a = sample_bilinear_linear(d, uv, sampler.wrap_u, sampler.wrap_v);
  const glm::vec4 b = sample_bilinear_linear(d + 1, uv, sampler.wrap_u, sampler.wrap_v);
  const glm::vec4 mixed = a + (b - a) * f;
  const float* encode = detail::srgb_encode_table();
  return {detail::srgb_encode(mixed.r, encode), detail::srgb_encode(mixed.g, encode),
          detail::srgb_encode(mixed.b, encode), mixed.a};
}

glm::vec4 Texture::sample_linear(glm::vec2 uv, glm::vec2 duv_dx, glm::vec2 duv_dy, const Sampler& sampler) const {
  if (!srgb_) return sample(uv, duv_dx, duv_dy, sampler);
  if (empty()) return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  if (sampler.filter == Filter::nearest) {
    const glm::vec4 t = sample_nearest(0, uv, sampler.wrap_u, sampler.wrap_v);
    const float* decode = detail::srgb_decode_table();
    const auto byte = [&](float v) { return decode[static_cast<int>(v * 255.0f + 0.5f)]; };
    return {byte(t.r), byte(t.g), byte(t.b), t.a};
  }
  // trilinear as sample() chooses its levels, without the final encoding.
  int level = 0;
  float f = 0.0f;
  if (sampler.filter == Filter::trilinear && level_count_ > 1) {
    const glm::vec2 size(levels_[0].fwidth, levels_[0].fheight);
    const float lod = std::log2(std::max(glm::length(duv_dx * size), glm::length(duv_dy * size)));
    if (lod > 0.0f) {
      const float max_level = static_cast<float>(level_count_ - 1);
      if (lod >= max_level) {
        level = level_count_ - 1;
      } else {
        level = static_cast<int>(lod);
        f = lod - static_cast<float>(level);
      }
    }
  }
  const glm::vec4 a = sample_bilinear_linear(level, uv, sampler.wrap_u, sampler.wrap_v);
  if (f == 0.0f) return a;
  const glm::vec4 b = sample_bilinear_linear(level + 1, uv, sampler.wrap_u, sampler.wrap_v);
  return a + (b - a) * f;
}

}  // namespace facet
