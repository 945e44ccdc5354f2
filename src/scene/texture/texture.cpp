// texture.cpp - texture storage, the mipmap chain, image-file loading (stb_image) and the benchmark checker.
#include "facet/texture.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "facet/error.hpp"
#include "core/file_util.hpp"
#include "scene/texture/decode.hpp"
#include "scene/texture/image_decode.hpp"

// The one stb_image implementation in facet, for TGA, BMP and Radiance .hdr only: PNG and JPEG go through libspng and
// libjpeg-turbo (image_decode.hpp), which fuzzing showed to be the safer readers of malformed files. A build
// without those (FACET_NO_IMAGE_CODECS) decodes PNG and JPEG with stb too. The dimension cap rejects absurd files
// early.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_TGA
#define STBI_ONLY_BMP
#define STBI_ONLY_HDR  // Radiance environments (io/environment_io.cpp)
#ifdef FACET_NO_IMAGE_CODECS
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#endif
#define STBI_MAX_DIMENSIONS 16384
#include "scene/texture/stb.hpp"

namespace facet {

namespace {

// Texels per stored row: the width, the wrap column, then padding to an odd number of 64-byte lines. Without it a
// 1024-texel row is 4,100 bytes, just over a power of two, so one column of 16 consecutive rows falls into the same
// L1 set, and the eight or more rows a minified block reads evict each other before the next block reuses them;
// with an odd number of lines per row, consecutive rows fall into consecutive sets. sphere:224: simulated L1
// misses on texel loads -16%.
int row_stride(int width) {
  constexpr int kTexelsPerLine = 64 / sizeof(std::uint32_t);
  const int lines = (width + 1 + kTexelsPerLine - 1) / kTexelsPerLine;
  return kTexelsPerLine * (lines % 2 == 0 ? lines + 1 : lines);
}
// Texels stored for every level of a width x height texture, each level's rows padded and followed by a wrap row.
std::size_t mip_chain_texels(int width, int height) {
  std::size_t total = 0;
  for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
    total += static_cast<std::size_t>(row_stride(w)) * (h + 1);
    if (w == 1 && h == 1) return total;
  }
}

}  // namespace

static_assert(kMaxTextureSize == STBI_MAX_DIMENSIONS);

Texture::Texture(int width, int height, std::vector<std::uint32_t> rgba, TexelEncoding encoding)
    : srgb_(encoding == TexelEncoding::srgb) {
  if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
    throw std::invalid_argument("texture size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1.." + std::to_string(kMaxTextureSize));
  if (rgba.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("texture of " + std::to_string(width) + "x" + std::to_string(height) + " given " +
                                std::to_string(rgba.size()) + " texels");
  const int stride = row_stride(width);
  levels_[0] = Level{width, height, stride, static_cast<float>(width), static_cast<float>(height), 0};
  level_count_ = 1;
  pow2_ = (width & (width - 1)) == 0 && (height & (height - 1)) == 0;
  // Room for the mipmaps too, so generate_mipmaps() does not move level 0 to a larger block.
  texels_.reserve(mip_chain_texels(width, height));
  texels_.resize(static_cast<std::size_t>(stride) * (height + 1));
  for (int y = 0; y < height; ++y)
    std::copy_n(rgba.begin() + static_cast<std::ptrdiff_t>(y) * width, width,
                texels_.begin() + static_cast<std::ptrdiff_t>(y) * stride);
  pad_level(0);
}

void Texture::pad_level(int level) {
  const Level& l = levels_[static_cast<std::size_t>(level)];
  std::uint32_t* base = texels_.data() + l.offset;
  for (int y = 0; y < l.height; ++y) {
    std::uint32_t* row = base + static_cast<std::size_t>(y) * l.stride;
    row[l.width] = row[0];
  }
  std::copy_n(base, l.stride, base + static_cast<std::size_t>(l.height) * l.stride);
}

glm::vec4 Texture::texel(int level, int x, int y) const {
  const Level& l = levels_[static_cast<std::size_t>(level)];
  return detail::unpack_bytes(texels_[l.offset + static_cast<std::size_t>(y) * l.stride + x]) / 255.0f;
}

namespace detail {

const float* srgb_decode_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[static_cast<std::size_t>(i)] =
          static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table.data();
}

const float* srgb_encode_table() {
  static const std::array<float, kSrgbEncodeSteps + 1> table = [] {
    std::array<float, kSrgbEncodeSteps + 1> t{};
    for (int i = 0; i <= kSrgbEncodeSteps; ++i) {
      const double x = static_cast<double>(i) / kSrgbEncodeSteps;
      t[static_cast<std::size_t>(i)] =
          static_cast<float>(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
    }
    return t;
  }();
  return table.data();
}

const float* srgb_decode_curve_table() {
  static const std::array<float, kSrgbEncodeSteps + 1> table = [] {
    std::array<float, kSrgbEncodeSteps + 1> t{};
    for (int i = 0; i <= kSrgbEncodeSteps; ++i) {
      const double c = static_cast<double>(i) / kSrgbEncodeSteps;
      t[static_cast<std::size_t>(i)] =
          static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table.data();
}

}  // namespace detail

namespace {

// How the texels of one axis of a level reduce to the next: destination texel d covers the source interval
// [d*ratio, (d+1)*ratio) with ratio = src/dst <= 3, so it touches at most 3 source texels; each is weighted by its
// overlap with that interval divided by ratio. For even sizes that is (1/2, 1/2).
struct AxisTaps {
  int first = 0, count = 0;
  float weight[3] = {0.0f, 0.0f, 0.0f};
};

std::vector<AxisTaps> axis_taps(int src, int dst) {
  std::vector<AxisTaps> taps(static_cast<std::size_t>(dst));
  const double ratio = static_cast<double>(src) / dst;
  for (int d = 0; d < dst; ++d) {
    const double lo = d * ratio, hi = (d + 1) * ratio;
    AxisTaps& t = taps[static_cast<std::size_t>(d)];
    t.first = static_cast<int>(lo);
    for (int s = t.first; s < src && s < hi && t.count < 3; ++s) {
      const double overlap = std::min<double>(s + 1, hi) - std::max<double>(s, lo);
      t.weight[t.count++] = static_cast<float>(overlap / ratio);
    }
  }
  return taps;
}

}  // namespace

void Texture::generate_mipmaps() {
  if (empty()) return;
  // Recompute from level 0, so calling this twice (or after changing nothing) gives the same chain.
  level_count_ = 1;
  texels_.resize(mip_chain_texels(width(), height()));

  std::vector<glm::vec4> row_sums;  // one source level reduced horizontally, for one destination row
  // Texels are averaged in linear light, 0..255: an sRGB texture's colour decoded, and the average encoded again
  // to the nearest byte, exactly: by the linear values where the encoded curve crosses each half step, starting
  // from the byte at the start of the linear value's 1/16 bucket (the curve is never steeper than 0.8 bytes a
  // bucket, so at most two steps follow).
  const float* decode = detail::srgb_decode_table();
  struct SrgbRounding {
    std::array<float, 256> half_step{};             // [b]: the lowest linear value that rounds above byte b
    std::array<std::uint8_t, 4096> bucket_start{};  // [q]: the byte linear value q / 16 rounds to
  };
  static const SrgbRounding rounding = [] {
    SrgbRounding r;
    for (int b = 0; b < 256; ++b) {
      const double c = (b + 0.5) / 255.0;
      r.half_step[static_cast<std::size_t>(b)] =
          b == 255 ? 3.0e38f
                   : static_cast<float>(255.0 * (c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4)));
    }
    std::size_t b = 0;
    for (std::size_t q = 0; q < r.bucket_start.size(); ++q) {
      while (static_cast<float>(q) / 16.0f >= r.half_step[b]) ++b;
      r.bucket_start[q] = static_cast<std::uint8_t>(b);
    }
    return r;
  }();
  const auto encode_byte = [&](float linear) {
    const int q = std::clamp(static_cast<int>(linear * 16.0f), 0, 4095);
    std::size_t b = rounding.bucket_start[static_cast<std::size_t>(q)];
    while (linear >= rounding.half_step[b]) ++b;
    return static_cast<float>(b);
  };
  const auto unpack = [&](std::uint32_t texel) {
    const glm::vec4 v = detail::unpack_bytes(texel);
    if (!srgb_) return v;
    const auto c = [&](float byte) { return decode[static_cast<int>(byte)] * 255.0f; };
    return glm::vec4(c(v.r), c(v.g), c(v.b), v.a);
  };
  // Rounded to the nearest byte; the clamp guards against weights summing a hair above 1.
  const auto pack = [&](glm::vec4 v) {
    const glm::vec4 rounded = glm::clamp(glm::floor(v + 0.5f), 0.0f, 255.0f);
    if (!srgb_) return rounded;
    return glm::vec4(encode_byte(v.r), encode_byte(v.g), encode_byte(v.b), rounded.a);
  };
  while (levels_[level_count_ - 1].width > 1 || levels_[level_count_ - 1].height > 1) {
    const Level& src = levels_[level_count_ - 1];
    const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    const Level dst{w,
                    h,
                    row_stride(w),
                    static_cast<float>(w),
                    static_cast<float>(h),
                    src.offset + static_cast<std::size_t>(src.stride) * (src.height + 1)};
    const auto store = [](std::uint32_t* out, glm::vec4 c) {
      *out = static_cast<std::uint32_t>(c.x) | static_cast<std::uint32_t>(c.y) << 8 |
             static_cast<std::uint32_t>(c.z) << 16 | static_cast<std::uint32_t>(c.w) << 24;
    };
    if (src.width == 2 * w && src.height == 2 * h) {
      // Halving both ways, the common case: each texel the mean of a 2x2 block. Weights of 1/2 scale exactly, so
      // this sums in the order the general filter below does and gives the same bits, with less bookkeeping.
      for (int y = 0; y < h; ++y) {
        const std::uint32_t* top = texels_.data() + src.offset + static_cast<std::size_t>(2 * y) * src.stride;
        const std::uint32_t* bottom = top + src.stride;
        std::uint32_t* out = texels_.data() + dst.offset + static_cast<std::size_t>(y) * dst.stride;
        for (int x = 0; x < w; ++x) {
          const glm::vec4 upper = unpack(top[2 * x]) + unpack(top[2 * x + 1]);
          const glm::vec4 lower = unpack(bottom[2 * x]) + unpack(bottom[2 * x + 1]);
          store(out + x, pack((upper + lower) * 0.25f));
        }
      }
      levels_[level_count_] = dst;
      pad_level(level_count_++);
      continue;
    }
    const std::vector<AxisTaps> tx = axis_taps(src.width, w), ty = axis_taps(src.height, h);
    row_sums.assign(static_cast<std::size_t>(w), glm::vec4(0.0f));
    for (int y = 0; y < h; ++y) {
      const AxisTaps& vy = ty[static_cast<std::size_t>(y)];
      std::fill(row_sums.begin(), row_sums.end(), glm::vec4(0.0f));
      for (int k = 0; k < vy.count; ++k) {
        const std::uint32_t* row = texels_.data() + src.offset + static_cast<std::size_t>(vy.first + k) * src.stride;
        for (int x = 0; x < w; ++x) {
          const AxisTaps& vx = tx[static_cast<std::size_t>(x)];
          glm::vec4 sum(0.0f);
          for (int m = 0; m < vx.count; ++m) sum += unpack(row[vx.first + m]) * vx.weight[m];
          row_sums[static_cast<std::size_t>(x)] += sum * vy.weight[k];
        }
      }
      std::uint32_t* out = texels_.data() + dst.offset + static_cast<std::size_t>(y) * dst.stride;
      for (int x = 0; x < w; ++x) store(out + x, pack(row_sums[static_cast<std::size_t>(x)]));
    }
    levels_[level_count_] = dst;
    pad_level(level_count_++);
  }
}


Texture load_texture(const std::filesystem::path& path, TexelEncoding encoding) {
  return decode_texture_file(read_image_file(path), encoding, path);
}

Texture decode_texture_file(std::span<const unsigned char> bytes, TexelEncoding encoding,
                            const std::filesystem::path& path) {
  const DecodedImage image = decode_image(bytes, kMaxTextureSize, path.string());
  const int w = image.width, h = image.height;
  // Image files store the top row first; texture row 0 is v = 0, the bottom (OpenGL's convention).
  std::vector<std::uint32_t> texels(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    const std::uint8_t* src = image.rgba.data() + static_cast<std::size_t>(h - 1 - y) * w * 4;
    std::uint32_t* dst = texels.data() + static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x, src += 4)
      dst[x] = std::uint32_t{src[0]} | std::uint32_t{src[1]} << 8 | std::uint32_t{src[2]} << 16 |
               std::uint32_t{src[3]} << 24;
  }
  Texture texture(w, h, std::move(texels), encoding);
  texture.generate_mipmaps();
  return texture;
}

Texture make_checker_texture(int size) {
  if (size < 1 || size > kMaxTextureSize)
    throw std::invalid_argument("checker texture size " + std::to_string(size) + " is outside 1.." +
                                std::to_string(kMaxTextureSize));
  // Exactly the reference's generator (glref.cpp make_checker), constants included; beyond 1727 texels the
  // gradient channels wrap modulo 256 there too, since they are stored as bytes.
  std::vector<std::uint32_t> texels(static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool light = (((x / 128) ^ (y / 128)) & 1) != 0;
      const std::uint32_t r = light ? 230u : static_cast<std::uint32_t>(40 + x / 8) & 0xffu;
      const std::uint32_t g = light ? 230u : 60u;
      const std::uint32_t b = light ? 230u : static_cast<std::uint32_t>(40 + y / 8) & 0xffu;
      texels[static_cast<std::size_t>(y) * size + x] = r | g << 8 | b << 16 | 0xffu << 24;
    }
  return Texture(size, size, std::move(texels));
}

}  // namespace facet
