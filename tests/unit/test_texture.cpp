// test_texture.cpp - texture sampling (filters, wrap modes, level of detail), mipmaps, the checker and loading.
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "facet/detail/dispatch.hpp"
#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/simd.hpp"
#include "facet/texture.hpp"
#include "support/scratch_dir.hpp"

namespace facet::texture_tests {
namespace {

std::uint32_t rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a = 255) {
  return r | g << 8 | b << 16 | a << 24;
}

glm::vec4 bytes(std::uint32_t r, std::uint32_t g, std::uint32_t b, std::uint32_t a = 255) {
  return glm::vec4(r, g, b, a) / 255.0f;
}

void expect_color(glm::vec4 actual, glm::vec4 expected, float tolerance = 1e-6f) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], tolerance) << "channel " << c;
}

std::filesystem::path scratch_dir() { return test::scratch_dir("texture"); }

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// 2x2: T(0,0) red-ish, T(1,0) green-ish, T(0,1) blue-ish, T(1,1) grey with alpha 0.
Texture two_by_two() { return Texture(2, 2, {rgba(200, 0, 0), rgba(0, 100, 0), rgba(0, 0, 40), rgba(80, 80, 80, 0)}); }

TEST(TextureSampling, NearestPicksTheTexelUnderTheUv) {
  const Texture t = two_by_two();
  const Sampler nearest{Filter::nearest};
  expect_color(t.sample({0.25f, 0.25f}, nearest), bytes(200, 0, 0));
  expect_color(t.sample({0.75f, 0.25f}, nearest), bytes(0, 100, 0));
  expect_color(t.sample({0.25f, 0.75f}, nearest), bytes(0, 0, 40));
  expect_color(t.sample({0.99f, 0.51f}, nearest), bytes(80, 80, 80, 0));
  expect_color(t.sample({0.5f, 0.0f}, nearest), bytes(0, 100, 0));  // u*2 = 1 exactly: texel 1
}

TEST(TextureSampling, BilinearFollowsTheGlFormula) {
  const Texture t = two_by_two();
  for (const Filter f : {Filter::bilinear, Filter::trilinear}) {
    const Sampler s{f};
    // s = u*2 - 0.5 = 0 at texel centres: exactly one texel.
    expect_color(t.sample({0.25f, 0.25f}, s), bytes(200, 0, 0));
    // The middle: the mean of all four.
    expect_color(t.sample({0.5f, 0.5f}, s), glm::vec4(70, 45, 30, 191.25f) / 255.0f);
    // s = 0.25: 3/4 of T(0,0) and 1/4 of T(1,0).
    expect_color(t.sample({0.375f, 0.25f}, s), glm::vec4(150, 25, 0, 255) / 255.0f);
    // t = 0.5, s = 0: halfway up between T(0,0) and T(0,1).
    expect_color(t.sample({0.25f, 0.5f}, s), glm::vec4(100, 0, 20, 255) / 255.0f);
    // Corner (0, 0) with repeat: i = -1 wraps to 1, so again the mean of all four.
    expect_color(t.sample({0.0f, 0.0f}, s), glm::vec4(70, 45, 30, 191.25f) / 255.0f);
  }
}

// The BENCHMARK.md section 7 formula written out directly, for any size and repeat wrapping.
glm::vec4 reference_bilinear_repeat(const Texture& t, glm::vec2 uv) {
  const int w = t.width(), h = t.height();
  const float s = uv.x * static_cast<float>(w) - 0.5f, tt = uv.y * static_cast<float>(h) - 0.5f;
  const int i = static_cast<int>(std::floor(s)), j = static_cast<int>(std::floor(tt));
  const float a = s - std::floor(s), b = tt - std::floor(tt);
  auto at = [&](int x, int y) { return t.texel(0, ((x % w) + w) % w, ((y % h) + h) % h) * 255.0f; };
  const glm::vec4 lo = at(i, j) * (1 - a) + at(i + 1, j) * a, hi = at(i, j + 1) * (1 - a) + at(i + 1, j + 1) * a;
  return (lo * (1 - b) + hi * b) / 255.0f;
}

TEST(TextureSampling, FastAndGeneralPathsMatchTheReferenceFormula) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::uint32_t> byte(0, 255);
  std::uniform_real_distribution<float> coord(-3.0f, 11.0f);
  for (const glm::ivec2 size : {glm::ivec2(8, 4), glm::ivec2(5, 3), glm::ivec2(1, 7)}) {  // pow2 = inline path
    std::vector<std::uint32_t> texels(static_cast<std::size_t>(size.x * size.y));
    for (auto& p : texels) p = rgba(byte(rng), byte(rng), byte(rng), byte(rng));
    const Texture t(size.x, size.y, texels);
    for (int k = 0; k < 2000; ++k) {
      const glm::vec2 uv(coord(rng), coord(rng));
      expect_color(t.sample(uv, Sampler{Filter::bilinear}), reference_bilinear_repeat(t, uv), 2e-5f);
    }
  }
}

// 4x1 texture, red = 0, 60, 120, 180 by column; the transposed 1x4 one checks wrap_v the same way.
TEST(TextureSampling, WrapModesOutsideTheUnitSquare) {
  const std::vector<std::uint32_t> texels = {rgba(0, 0, 0), rgba(60, 0, 0), rgba(120, 0, 0), rgba(180, 0, 0)};
  const Texture row(4, 1, texels), column(1, 4, texels);
  struct Case {
    Filter filter;
    Wrap wrap;
    float coord, red;
  };
  const Case cases[] = {
      // nearest: index floor(4u)
      {Filter::nearest, Wrap::repeat, 1.125f, 0},
      {Filter::nearest, Wrap::clamp, 1.125f, 180},
      {Filter::nearest, Wrap::mirror, 1.125f, 180},
      {Filter::nearest, Wrap::repeat, -0.125f, 180},
      {Filter::nearest, Wrap::clamp, -0.125f, 0},
      {Filter::nearest, Wrap::mirror, -0.125f, 0},
      {Filter::nearest, Wrap::repeat, 1.875f, 180},
      {Filter::nearest, Wrap::mirror, 1.875f, 0},
      {Filter::nearest, Wrap::mirror, 1.375f, 120},
      {Filter::nearest, Wrap::mirror, 2.125f, 0},
      {Filter::nearest, Wrap::repeat, -1.125f, 180},
      {Filter::nearest, Wrap::mirror, -1.125f, 180},
      {Filter::nearest, Wrap::clamp, -7.0f, 0},
      {Filter::nearest, Wrap::clamp, 9.0f, 180},
      // bilinear: s = 4u - 0.5
      {Filter::bilinear, Wrap::repeat, 1.0f, 90},
      {Filter::bilinear, Wrap::clamp, 1.0f, 180},
      {Filter::bilinear, Wrap::mirror, 1.0f, 180},
      {Filter::bilinear, Wrap::repeat, 0.0f, 90},
      {Filter::bilinear, Wrap::clamp, 0.0f, 0},
      {Filter::bilinear, Wrap::mirror, 0.0f, 0},
      {Filter::bilinear, Wrap::repeat, -0.25f, 150},
      {Filter::bilinear, Wrap::mirror, -0.25f, 30},
      {Filter::bilinear, Wrap::clamp, 3.0f, 180},
      {Filter::bilinear, Wrap::mirror, 1.25f, 150},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("filter " + std::to_string(static_cast<int>(c.filter)) + " wrap " +
                 std::to_string(static_cast<int>(c.wrap)) + " at " + std::to_string(c.coord));
    // The other axis gets a wrap mode and coordinate that must not matter (size 1).
    EXPECT_NEAR(row.sample({c.coord, 5.3f}, Sampler{c.filter, c.wrap, Wrap::mirror}).x, c.red / 255.0f, 1e-6f);
    EXPECT_NEAR(column.sample({-2.7f, c.coord}, Sampler{c.filter, Wrap::clamp, c.wrap}).x, c.red / 255.0f, 1e-6f);
    if (c.wrap == Wrap::repeat) {  // both axes repeat: the inline fast path for bilinear
      EXPECT_NEAR(row.sample({c.coord, 5.3f}, Sampler{c.filter}).x, c.red / 255.0f, 1e-6f);
      EXPECT_NEAR(column.sample({-2.7f, c.coord}, Sampler{c.filter}).x, c.red / 255.0f, 1e-6f);
    }
  }
}

TEST(TextureSampling, HugeAndNonFiniteCoordinatesAreSafe) {
  const Texture t = two_by_two();
  for (const float u : {1e30f, -1e30f, INFINITY, -INFINITY}) {
    for (const Filter f : {Filter::nearest, Filter::bilinear})
      for (const Wrap w : {Wrap::repeat, Wrap::clamp, Wrap::mirror}) (void)t.sample({u, u}, Sampler{f, w, w});
  }
  (void)t.sample({NAN, 0.5f}, Sampler{Filter::bilinear});
  (void)t.sample({0.5f, 0.5f}, {NAN, 0.0f}, {0.0f, NAN}, Sampler{});
  const Texture empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.levels(), 0);
  expect_color(empty.sample({0.5f, 0.5f}, Sampler{}), glm::vec4(0, 0, 0, 1));
}

// sample_lanes as the tile function runs it: compiled in each dispatch clone, the one for this CPU called.
void sample_lanes_dispatched(const Texture& t, const simd::Vec2& uv, const Sampler& s, simd::Color& out) {
  facet::detail::at_cpu_level([&]() __attribute__((always_inline)) {
    out = t.sample_lanes(uv, s);
  });
}

// The lane path gives sample()'s values bit for bit, lane by lane: coordinates below zero (where floor and
// truncation part), on texel centres and edges, huge, infinite and NaN. The 8x4 texture takes the inline
// power-of-two path; 5x3 falls back to sample() per lane.
TEST(TextureSampling, LanesMatchTheScalarSampleBitForBit) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<std::uint32_t> byte(0, 255);
  std::uniform_real_distribution<float> coord(-3.0f, 11.0f);
  const float special[] = {-0.0f,   0.0f,        1.0f / 16.0f, -1.0f / 16.0f, 0.5f, -0.5f,
                           1e30f,   -1e30f,      INFINITY,     -INFINITY,     NAN,  3.0e9f,
                           -3.0e9f, 1.0f / 8.0f, -1.0f / 8.0f, 7.9999995f};
  for (const glm::ivec2 size : {glm::ivec2(8, 4), glm::ivec2(5, 3)}) {
    std::vector<std::uint32_t> texels(static_cast<std::size_t>(size.x * size.y));
    for (auto& p : texels) p = rgba(byte(rng), byte(rng), byte(rng), byte(rng));
    for (const TexelEncoding encoding : {TexelEncoding::linear, TexelEncoding::srgb}) {
      const Texture t(size.x, size.y, texels, encoding);
      for (const Sampler sampler : {Sampler{Filter::bilinear}, Sampler{Filter::trilinear}}) {
        for (int batch = 0; batch < 200; ++batch) {
          simd::Vec2 uv;
          for (int k = 0; k < simd::kLanes; ++k) {
            uv.x[k] = batch == 0 ? special[k] : coord(rng);
            uv.y[k] = batch == 1 ? special[k] : coord(rng);
          }
          simd::Color lanes;
          sample_lanes_dispatched(t, uv, sampler, lanes);
          for (int k = 0; k < simd::kLanes; ++k) {
            const glm::vec4 scalar = t.sample(glm::vec2(uv.x[k], uv.y[k]), sampler);
            const float got[4] = {lanes.r[k], lanes.g[k], lanes.b[k], lanes.a[k]};
            for (int c = 0; c < 4; ++c)
              ASSERT_EQ(std::bit_cast<std::uint32_t>(got[c]), std::bit_cast<std::uint32_t>(scalar[c]))
                  << size.x << "x" << size.y << " batch " << batch << " lane " << k << " channel " << c << " at "
                  << uv.x[k] << ", " << uv.y[k] << (encoding == TexelEncoding::srgb ? " (sRGB)" : "");
          }
        }
      }
    }
  }
}

// sample_linear_lanes as the PBR shader's lanes run it, in the dispatch clone for this CPU.
void sample_linear_lanes_dispatched(const Texture& t, const simd::Vec2& uv, const simd::Vec2& dx, const simd::Vec2& dy,
                                    const Sampler& s, simd::Color& out) {
  facet::detail::at_cpu_level([&]() __attribute__((always_inline)) {
    out = t.sample_linear_lanes(uv, dx, dy, s);
  });
}

// The lane path of sample_linear gives its values bit for bit, lane by lane: derivatives from far below a texel
// (level 0) through every level to beyond the last, exactly on whole levels of detail, zero, infinite and NaN. The
// mipmapped 16x8 sRGB texture takes the lane path (trilinear, repeat); clamping, a linear texture and a 5x3 one
// fall back to sample_linear per lane.
TEST(TextureSampling, LinearLanesMatchTheScalarSampleLinearBitForBit) {
  std::mt19937 rng(13);
  std::uniform_int_distribution<std::uint32_t> byte(0, 255);
  std::uniform_real_distribution<float> coord(-3.0f, 11.0f), exponent(-8.0f, 2.0f);
  const float special[] = {0.0f,      -0.0f,         1.0f / 16.0f, 1.0f / 8.0f, 1.0f / 4.0f, 1.0f / 2.0f,
                           1.0f,      3.0f / 16.0f,  1e30f,        INFINITY,    NAN,         -1.0f / 16.0f,
                           1e-30f,    -INFINITY,     0.75f,        2.0f};
  Sampler clamped{Filter::trilinear};
  clamped.wrap_u = Wrap::clamp;
  for (const glm::ivec2 size : {glm::ivec2(16, 8), glm::ivec2(5, 3)}) {
    std::vector<std::uint32_t> texels(static_cast<std::size_t>(size.x * size.y));
    for (auto& p : texels) p = rgba(byte(rng), byte(rng), byte(rng), byte(rng));
    for (const TexelEncoding encoding : {TexelEncoding::srgb, TexelEncoding::linear}) {
      Texture t(size.x, size.y, texels, encoding);
      t.generate_mipmaps();
      for (const Sampler sampler : {Sampler{Filter::trilinear}, clamped, Sampler{Filter::bilinear}}) {
        for (int batch = 0; batch < 300; ++batch) {
          simd::Vec2 uv, dx, dy;
          for (int k = 0; k < simd::kLanes; ++k) {
            uv.x[k] = coord(rng), uv.y[k] = coord(rng);
            const float step = std::exp2(exponent(rng));
            dx.x[k] = batch == 0 ? special[k] : step, dx.y[k] = batch == 1 ? special[k] : 0.0f;
            dy.x[k] = 0.0f, dy.y[k] = batch == 2 ? special[k] : step * 0.5f;
          }
          simd::Color lanes;
          sample_linear_lanes_dispatched(t, uv, dx, dy, sampler, lanes);
          for (int k = 0; k < simd::kLanes; ++k) {
            const glm::vec4 scalar = t.sample_linear(glm::vec2(uv.x[k], uv.y[k]), glm::vec2(dx.x[k], dx.y[k]),
                                                     glm::vec2(dy.x[k], dy.y[k]), sampler);
            const float got[4] = {lanes.r[k], lanes.g[k], lanes.b[k], lanes.a[k]};
            for (int c = 0; c < 4; ++c)
              ASSERT_EQ(std::bit_cast<std::uint32_t>(got[c]), std::bit_cast<std::uint32_t>(scalar[c]))
                  << size.x << "x" << size.y << " batch " << batch << " lane " << k << " channel " << c << " at "
                  << uv.x[k] << ", " << uv.y[k] << " step " << dx.x[k] << ", " << dy.y[k];
          }
        }
      }
    }
  }
}

// Lane by lane, sample_linear_lanes reads only the lanes asked for (a multisampled edge's later shading rounds
// colour a few of a strip's pixels): those match sample_linear, the others are 0.
TEST(TextureSampling, LinearLanesSampleOnlyTheLanesAskedFor) {
  std::vector<std::uint32_t> texels(5 * 3);
  for (std::size_t i = 0; i < texels.size(); ++i)
    texels[i] = rgba(static_cast<std::uint8_t>(40 + 13 * i), 200, static_cast<std::uint8_t>(9 * i), 255);
  Texture t(5, 3, texels, TexelEncoding::srgb);  // not a power of two: lane by lane
  t.generate_mipmaps();
  const Sampler sampler{Filter::trilinear};
  simd::Vec2 uv, dx, dy;
  for (int k = 0; k < simd::kLanes; ++k) {
    uv.x[k] = 0.05f * static_cast<float>(k), uv.y[k] = 0.9f - 0.04f * static_cast<float>(k);
    dx.x[k] = 0.1f, dx.y[k] = 0.0f, dy.x[k] = 0.0f, dy.y[k] = 0.2f;
  }
  const unsigned asked = 0b1010'0000'1100'0001u;
  simd::Color lanes;
  facet::detail::at_cpu_level([&]() __attribute__((always_inline)) {
    lanes = t.sample_linear_lanes(uv, dx, dy, sampler, asked);
  });
  for (int k = 0; k < simd::kLanes; ++k) {
    const glm::vec2 at(uv.x[k], uv.y[k]), step_x(dx.x[k], dx.y[k]), step_y(dy.x[k], dy.y[k]);
    const glm::vec4 scalar = (asked >> k & 1u) ? t.sample_linear(at, step_x, step_y, sampler) : glm::vec4(0.0f);
    EXPECT_EQ(lanes.r[k], scalar.r) << k;
    EXPECT_EQ(lanes.g[k], scalar.g) << k;
    EXPECT_EQ(lanes.b[k], scalar.b) << k;
    EXPECT_EQ(lanes.a[k], scalar.a) << k;
  }
  EXPECT_GT(lanes.g[0], 0.5f);  // an asked lane holds a texel's green
}

// IEC 61966-2-1's curves, in double precision.
double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }

TEST(TextureSrgb, TablesFollowTheStandardCurves) {
  const float* decode = detail::srgb_decode_table();
  const float* encode = detail::srgb_encode_table();
  EXPECT_EQ(decode[0], 0.0f);
  EXPECT_EQ(decode[255], 1.0f);
  EXPECT_NEAR(decode[128], 0.2158605, 1e-6);
  for (int b = 0; b < 256; ++b) {
    EXPECT_NEAR(decode[b], srgb_to_linear(b / 255.0), 1e-7) << b;
    // Decoding and encoding again gives the byte back.
    EXPECT_EQ(std::lround(detail::srgb_encode(decode[b], encode) * 255.0f), b);
  }
  for (int i = 0; i <= 100000; ++i) {
    const double x = i / 100000.0;
    ASSERT_NEAR(detail::srgb_encode(static_cast<float>(x), encode), linear_to_srgb(x), 2e-5) << x;
  }
  EXPECT_EQ(detail::srgb_encode(-1.0f, encode), 0.0f);
  EXPECT_EQ(detail::srgb_encode(NAN, encode), 0.0f);
  EXPECT_EQ(detail::srgb_encode(7.0f, encode), 1.0f);
}

// Half way between a black and a white texel is half the light: sRGB 0.735, not the 0.5 of blending the codes.
TEST(TextureSrgb, BilinearBlendsInLinearLight) {
  const std::vector<std::uint32_t> black_white = {rgba(0, 0, 0, 0), rgba(255, 255, 255, 255)};
  const glm::vec4 code_blend = Texture(2, 1, black_white).sample({0.5f, 0.5f}, Sampler{Filter::bilinear});
  const Texture srgb(2, 1, black_white, TexelEncoding::srgb);
  EXPECT_EQ(srgb.encoding(), TexelEncoding::srgb);
  const float half_light = static_cast<float>(linear_to_srgb(0.5));
  expect_color(code_blend, glm::vec4(0.5f));
  for (const Wrap wrap : {Wrap::repeat, Wrap::clamp}) {  // the inline power-of-two path and the general one
    const Sampler sampler{Filter::bilinear, wrap, wrap};
    expect_color(srgb.sample({0.5f, 0.5f}, sampler), glm::vec4(half_light, half_light, half_light, 0.5f), 2e-5f);
  }
  // Nearest filtering and texel() give the stored codes.
  expect_color(srgb.sample({0.74f, 0.5f}, Sampler{Filter::nearest}), glm::vec4(1.0f));
  expect_color(srgb.texel(0, 0, 0), glm::vec4(0.0f));
}

// A black and white checker's next level is the average light, sRGB 188, where averaging the codes gives 128; and
// trilinear filtering blends the two levels in linear light as well.
TEST(TextureSrgb, MipmapsAndTrilinearAverageLight) {
  const std::vector<std::uint32_t> checker = {rgba(0, 0, 0), rgba(255, 255, 255), rgba(255, 255, 255), rgba(0, 0, 0)};
  Texture codes(2, 2, checker), light(2, 2, checker, TexelEncoding::srgb);
  codes.generate_mipmaps();
  light.generate_mipmaps();
  ASSERT_EQ(light.levels(), 2);
  expect_color(codes.texel(1, 0, 0), bytes(128, 128, 128));
  expect_color(light.texel(1, 0, 0), bytes(188, 188, 188));
  // lod 0.5 at the centre: level 0 blends all four texels (half light), level 1 is 188; half of each, in light.
  const Sampler trilinear{Filter::trilinear};
  const glm::vec2 step(std::sqrt(2.0f) / 2.0f, 0.0f);  // sqrt(2) texels of level 0 per pixel: lod 0.5
  const double expected = linear_to_srgb(0.5 * (0.5 + srgb_to_linear(188 / 255.0)));
  const glm::vec4 got = light.sample({0.5f, 0.5f}, step, glm::vec2(0.0f), trilinear);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected, 5e-5) << c;
  EXPECT_NEAR(got.a, 1.0f, 1e-6f);
}

// The SSE2 split and blend that x86-64 uses must give exactly what the portable code gives on other machines.
TEST(TextureSampling, Sse2AndPortableHelpersAgreeBitForBit) {
#if defined(FACET_TEXTURE_SSE2)
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-3000.0f, 3000.0f);
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  std::vector<float> values = {0.0f,        -0.0f, 0.5f,  -0.5f, 1.0f,   -1.0f,    1e-30f,    -1e-30f, 8388607.5f,
                               -8388607.5f, 2e9f,  -2e9f, 1e38f, -1e38f, INFINITY, -INFINITY, NAN};
  for (int k = 0; k < 20000; ++k) values.push_back(coordinate(rng));
  const auto same_bits = [](float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
  };
  for (std::size_t k = 0; k < values.size(); ++k) {
    const float s = values[k], t = values[(k * 7 + 3) % values.size()];
    const detail::Split fast = detail::split_floor_sse2(s, t), portable = detail::split_floor_portable(s, t);
    ASSERT_EQ(fast.i, portable.i) << "s = " << s;
    ASSERT_EQ(fast.j, portable.j) << "t = " << t;
    ASSERT_TRUE(same_bits(fast.alpha, portable.alpha)) << "s = " << s;
    ASSERT_TRUE(same_bits(fast.beta, portable.beta)) << "t = " << t;
  }
  std::uniform_int_distribution<std::uint64_t> pair;
  for (int k = 0; k < 20000; ++k) {
    const std::uint64_t bottom = pair(rng), top = pair(rng);
    const float alpha = weight(rng), beta = weight(rng);
    const glm::vec4 fast = detail::blend_sse2(bottom, top, alpha, beta);
    const glm::vec4 portable = detail::blend_portable(bottom, top, alpha, beta);
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(same_bits(fast[c], portable[c])) << "channel " << c;
  }
#else
  GTEST_FAIL() << "this test runs on x86-64, where the SSE2 helpers exist";
#endif
}

TEST(TextureSampling, ConstructorRejectsBadSizes) {
  EXPECT_THROW(Texture(0, 1, {}), std::invalid_argument);
  EXPECT_THROW(Texture(2, 2, std::vector<std::uint32_t>(3)), std::invalid_argument);
  EXPECT_THROW(Texture(kMaxTextureSize + 1, 1, std::vector<std::uint32_t>(kMaxTextureSize + 1)), std::invalid_argument);
}

std::vector<glm::ivec2> chain(int w, int h) {
  Texture t(w, h, std::vector<std::uint32_t>(static_cast<std::size_t>(w) * h, rgba(1, 2, 3)));
  EXPECT_EQ(t.levels(), 1);
  t.generate_mipmaps();
  std::vector<glm::ivec2> sizes;
  for (int l = 0; l < t.levels(); ++l) sizes.emplace_back(t.level_width(l), t.level_height(l));
  // A constant image stays constant on every level.
  expect_color(t.texel(t.levels() - 1, 0, 0), bytes(1, 2, 3));
  return sizes;
}

TEST(TextureMipmaps, ChainSizes) {
  std::vector<glm::ivec2> expected;
  for (int s = 1024; s >= 1; s /= 2) expected.emplace_back(s, s);
  EXPECT_EQ(chain(1024, 1024), expected);
  EXPECT_EQ(chain(300, 17),
            (std::vector<glm::ivec2>{{300, 17}, {150, 8}, {75, 4}, {37, 2}, {18, 1}, {9, 1}, {4, 1}, {2, 1}, {1, 1}}));
  EXPECT_EQ(chain(1, 1), (std::vector<glm::ivec2>{{1, 1}}));
  EXPECT_EQ(chain(1, 4), (std::vector<glm::ivec2>{{1, 4}, {1, 2}, {1, 1}}));
}

TEST(TextureMipmaps, BoxFilterOfLevelOne) {
  // 4x4; level 1 texel (x, y) averages the 2x2 block (2x..2x+1, 2y..2y+1), rounded to nearest.
  std::vector<std::uint32_t> texels(16);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      texels[static_cast<std::size_t>(y * 4 + x)] = rgba(x * 10 + y, 17 * y, x == y ? 255 : 0, 255 - x);
  Texture t(4, 4, texels);
  t.generate_mipmaps();
  ASSERT_EQ(t.levels(), 3);
  // Block (0, 0): red 0, 10, 1, 11 -> 5.5 -> 6; green 0, 0, 17, 17 -> 8.5 -> 9; blue 255, 0, 0, 255 -> 127.5 -> 128;
  // alpha 255, 254, 255, 254 -> 254.5 -> 255.
  expect_color(t.texel(1, 0, 0), bytes(6, 9, 128, 255));
  // Block (1, 0): red 20, 30, 21, 31 -> 25.5 -> 26; green 8.5 -> 9; blue 0; alpha 253, 252 -> 252.5 -> 253.
  expect_color(t.texel(1, 1, 0), bytes(26, 9, 0, 253));
  // Block (1, 1): red 22, 32, 23, 33 -> 27.5 -> 28; green 34, 51 -> 42.5 -> 43; blue 255, 0, 0, 255 -> 128.
  expect_color(t.texel(1, 1, 1), bytes(28, 43, 128, 253));
  // Block (0, 1): red 2, 12, 3, 13 -> 7.5 -> 8; green 43; blue 0; alpha 255.
  expect_color(t.texel(1, 0, 1), bytes(8, 43, 0, 255));
  // Level 2 averages level 1: red (6 + 26 + 8 + 28) / 4, green (9 + 9 + 43 + 43) / 4, and so on.
  expect_color(t.texel(2, 0, 0), bytes(17, 26, 64, 254));
}

TEST(TextureMipmaps, NonPowerOfTwoIsAreaWeighted) {
  // 5 -> 2: texel 0 covers [0, 2.5) (weights .4 .4 .2), texel 1 covers [2.5, 5) (.2 .4 .4).
  Texture t(5, 1, {rgba(0, 0, 0), rgba(100, 0, 0), rgba(200, 0, 0), rgba(50, 0, 0), rgba(250, 0, 0)});
  t.generate_mipmaps();
  ASSERT_EQ(t.levels(), 3);
  EXPECT_NEAR(t.texel(1, 0, 0).x * 255.0f, 80.0f, 1e-4f);
  EXPECT_NEAR(t.texel(1, 1, 0).x * 255.0f, 160.0f, 1e-4f);
  EXPECT_NEAR(t.texel(2, 0, 0).x * 255.0f, 120.0f, 1e-4f);
  // 3x3 -> 1x1: the plain mean of all nine.
  std::vector<std::uint32_t> nine;
  for (int k = 0; k < 9; ++k) nine.push_back(rgba(k * 20, 0, 0));
  Texture u(3, 3, nine);
  u.generate_mipmaps();
  ASSERT_EQ(u.levels(), 2);
  EXPECT_NEAR(u.texel(1, 0, 0).x * 255.0f, 80.0f, 1e-4f);
}

TEST(TextureSampling, TrilinearLevelFromDerivatives) {
  // 8x8 with red = 30x: level 0 column 0 is 0, level 1 (mean of 0, 30) 15, level 2 45, level 3 105. With clamp
  // wrapping, uv (0, 0) reads exactly texel (0, 0) of any level, so the result shows which levels were used.
  std::vector<std::uint32_t> texels(64);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) texels[static_cast<std::size_t>(y * 8 + x)] = rgba(30 * x, 0, 0);
  Texture t(8, 8, texels);
  const Sampler tri{Filter::trilinear, Wrap::clamp, Wrap::clamp};
  const glm::vec2 uv(0.0f, 0.0f);
  auto red = [&](float texels_x, float texels_y, const Sampler& s) {
    return t.sample(uv, {texels_x / 8.0f, 0.0f}, {0.0f, texels_y / 8.0f}, s).x * 255.0f;
  };
  EXPECT_NEAR(red(4, 0, tri), 0.0f, 1e-4f);  // no mipmaps yet: level 0 whatever the derivatives
  t.generate_mipmaps();
  ASSERT_EQ(t.levels(), 4);
  EXPECT_NEAR(red(0.5f, 0.25f, tri), 0.0f, 1e-4f);                 // magnification
  EXPECT_NEAR(red(1, 1, tri), 0.0f, 1e-4f);                        // 1 texel per pixel: level 0
  EXPECT_NEAR(red(2, 0, tri), 15.0f, 1e-4f);                       // level 1
  EXPECT_NEAR(red(4, 1, tri), 45.0f, 1e-4f);                       // 4 texels: level 2
  EXPECT_NEAR(red(0, 4, tri), 45.0f, 1e-4f);                       // the longer derivative decides
  EXPECT_NEAR(red(std::sqrt(2.0f), 0, tri), 7.5f, 1e-3f);          // lod 0.5: halfway between levels 0 and 1
  EXPECT_NEAR(red(2.0f * std::sqrt(2.0f), 0, tri), 30.0f, 1e-3f);  // lod 1.5: between 15 and 45
  EXPECT_NEAR(red(std::pow(2.0f, 2.25f), 0, tri), 60.0f, 1e-3f);   // lod 2.25: 45 + (105 - 45) / 4
  EXPECT_NEAR(red(100, 100, tri), 105.0f, 1e-4f);                  // beyond the last level: the 1x1 level
  // GL_NEAREST and GL_LINEAR ignore mipmaps.
  EXPECT_NEAR(red(4, 4, Sampler{Filter::bilinear, Wrap::clamp, Wrap::clamp}), 0.0f, 1e-4f);
  EXPECT_NEAR(red(4, 4, Sampler{Filter::nearest, Wrap::clamp, Wrap::clamp}), 0.0f, 1e-4f);
  // The two-argument overload never uses mipmaps.
  EXPECT_NEAR(t.sample(uv, tri).x * 255.0f, 0.0f, 1e-4f);
}

TEST(CheckerTexture, TexelsFollowTheBenchmarkDefinition) {
  const Texture t = make_checker_texture();
  ASSERT_EQ(t.width(), 1024);
  ASSERT_EQ(t.height(), 1024);
  EXPECT_EQ(t.levels(), 1);
  expect_color(t.texel(0, 0, 0), bytes(40, 60, 40));
  expect_color(t.texel(0, 127, 0), bytes(55, 60, 40));
  expect_color(t.texel(0, 128, 0), bytes(230, 230, 230));
  expect_color(t.texel(0, 0, 128), bytes(230, 230, 230));
  expect_color(t.texel(0, 128, 128), bytes(40 + 16, 60, 40 + 16));
  expect_color(t.texel(0, 300, 100), bytes(77, 60, 52));
  expect_color(t.texel(0, 200, 300), bytes(230, 230, 230));
  expect_color(t.texel(0, 1023, 1023), bytes(167, 60, 167));
  // Row 0 is v = 0: the texel centre (x + 0.5, y + 0.5) / 1024 samples exactly texel (x, y).
  expect_color(t.sample({300.5f / 1024, 100.5f / 1024}, Sampler{Filter::bilinear}), bytes(77, 60, 52));
  // Across the cell edge at x = 128: half of (55, 60, 40) and half of (230, 230, 230).
  expect_color(t.sample({128.0f / 1024, 0.5f / 1024}, Sampler{Filter::bilinear}),
               glm::vec4(142.5f, 145.0f, 135.0f, 255.0f) / 255.0f);
  EXPECT_EQ(make_checker_texture(16).width(), 16);
  EXPECT_THROW(make_checker_texture(0), std::invalid_argument);
}

TEST(TextureLoad, JpegFromAssimpTestModels) {
  const std::filesystem::path jpeg = "/usr/share/assimp/models/OBJ/SpiderTex.jpg";
  if (!std::filesystem::exists(jpeg)) GTEST_SKIP() << jpeg << " missing (Debian package assimp-testmodels)";
  const Texture t = load_texture(jpeg);
  ASSERT_GT(t.width(), 0);
  ASSERT_GT(t.height(), 0);
  EXPECT_EQ(t.levels(), static_cast<int>(std::floor(std::log2(std::max(t.width(), t.height())))) + 1);
  // read_png decodes any stb format top row first: texture row y is image row h-1-y.
  int w = 0, h = 0;
  const std::vector<std::uint8_t> image = read_png(jpeg, w, h);
  ASSERT_EQ(w, t.width());
  ASSERT_EQ(h, t.height());
  for (const glm::ivec2 p : {glm::ivec2(0, 0), glm::ivec2(w - 1, 0), glm::ivec2(w / 3, h / 2), glm::ivec2(5, h - 1)}) {
    const std::uint8_t* px = &image[(static_cast<std::size_t>(h - 1 - p.y) * w + p.x) * 4];
    expect_color(t.texel(0, p.x, p.y), bytes(px[0], px[1], px[2], px[3]));
  }
}

TEST(TextureLoad, PngIsFlippedSoRowZeroIsTheBottom) {
  const std::filesystem::path png = scratch_dir() / "three_by_two.png";
  // Top row first in the file: red, green, blue / then the bottom row: white, black, half-transparent grey.
  const std::vector<std::uint8_t> pixels = {255, 0,   0,   255, 0, 255, 0, 255, 0,   0,   255, 255,
                                            255, 255, 255, 255, 0, 0,   0, 255, 128, 128, 128, 64};
  write_png(png, 3, 2, pixels);
  const Texture t = load_texture(png);
  EXPECT_EQ(t.encoding(), TexelEncoding::srgb);  // image files hold colour unless the caller says otherwise
  EXPECT_EQ(load_texture(png, TexelEncoding::linear).encoding(), TexelEncoding::linear);
  ASSERT_EQ(t.width(), 3);
  ASSERT_EQ(t.height(), 2);
  EXPECT_EQ(t.levels(), 2);
  expect_color(t.texel(0, 0, 0), bytes(255, 255, 255));
  expect_color(t.texel(0, 2, 0), bytes(128, 128, 128, 64));
  expect_color(t.texel(0, 1, 1), bytes(0, 255, 0));
  expect_color(t.sample({0.1f, 0.9f}, Sampler{Filter::nearest}), bytes(255, 0, 0));  // v near 1: the top row
}

TEST(TextureLoad, UncompressedTgaWithBottomLeftOrigin) {
  const std::filesystem::path tga = scratch_dir() / "two_by_two.tga";
  // 18-byte header: type 2 (true colour), 2x2, 32 bits, descriptor 8 (8 alpha bits, origin bottom left).
  std::string file = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 32, 8};
  // BGRA, stored bottom row first because of the origin.
  const unsigned char data[] = {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 200, 1, 2, 3, 4};
  file.append(reinterpret_cast<const char*>(data), sizeof data);
  write_bytes(tga, file);
  const Texture t = load_texture(tga);
  ASSERT_EQ(t.width(), 2);
  ASSERT_EQ(t.height(), 2);
  expect_color(t.texel(0, 0, 0), bytes(30, 20, 10));
  expect_color(t.texel(0, 1, 0), bytes(60, 50, 40));
  expect_color(t.texel(0, 0, 1), bytes(90, 80, 70, 200));
  expect_color(t.texel(0, 1, 1), bytes(3, 2, 1, 4));
}

void expect_input_error(const std::filesystem::path& path, const std::string& reason_part) {
  try {
    (void)load_texture(path);
    ADD_FAILURE() << "no exception for " << path;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(reason_part), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(TextureLoad, ErrorsNameTheFile) {
  const std::filesystem::path dir = scratch_dir();
  expect_input_error(dir / "missing.png", "no such file");
  write_bytes(dir / "empty.png", "");
  expect_input_error(dir / "empty.png", "empty");
  write_bytes(dir / "garbage.png", "this is not an image at all, just some text\n");
  expect_input_error(dir / "garbage.png", "stb_image");
  expect_input_error(dir, "not a regular file");
  // A valid TGA header claiming 20000x1 texels.
  write_bytes(dir / "huge.tga", std::string({0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x20, 0x4e, 1, 0, 32, 8}));
  expect_input_error(dir / "huge.tga", "");
  // A truncated PNG: the signature and nothing else; a JPEG that stops after its start marker.
  write_bytes(dir / "truncated.png", "\x89PNG\r\n\x1a\n");
  expect_input_error(dir / "truncated.png", "cannot decode PNG (libspng: ");
  write_bytes(dir / "truncated.jpg", "\xff\xd8\xff\xe0");
  expect_input_error(dir / "truncated.jpg", "cannot decode JPEG (libjpeg-turbo: ");
}

// A header may declare no more texels than its file's bytes can describe, whatever the format: each refused here
// before a texel is allocated, and each one byte larger (or one texel smaller) decoded.
TEST(TextureLoad, DeclaredSizeMustBeBackedByTheFile) {
  const std::filesystem::path dir = scratch_dir();
  const auto u16 = [](unsigned v) { return std::string{static_cast<char>(v & 255), static_cast<char>(v >> 8)}; };
  const auto u32 = [&](unsigned v) { return u16(v & 0xffff) + u16(v >> 16); };
  // An uncompressed 24-bit BMP of W x H: rows padded to 4 bytes.
  const auto bmp = [&](unsigned w, unsigned h, std::size_t pixel_bytes) {
    return "BM" + u32(static_cast<unsigned>(54 + pixel_bytes)) + u32(0) + u32(54) + u32(40) + u32(w) + u32(h) +
           u16(1) + u16(24) + u32(0) + u32(0) + u32(0) + u32(0) + u32(0) + u32(0) + std::string(pixel_bytes, '\x40');
  };
  // 9,985 x 8,229 texels in 485 KB: under the old rule of 256 texels a byte, decoded into 330 MB.
  write_bytes(dir / "huge.bmp", bmp(9985, 8229, 485'000));
  expect_input_error(dir / "huge.bmp", "BMP declares 9985x8229 texels, more than its bytes can hold (needs 246507924");
  write_bytes(dir / "short.bmp", bmp(5, 3, 3 * 16 - 1));  // 5 texels a row: 15 bytes, padded to 16
  expect_input_error(dir / "short.bmp", "needs 48, has 47");
  write_bytes(dir / "exact.bmp", bmp(5, 3, 3 * 16));
  EXPECT_EQ(load_texture(dir / "exact.bmp").width(), 5);

  // An uncompressed TGA of 4 x 2 texels at 32 bits needs 32 bytes after its header.
  const std::string tga_header{0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 2, 0, 32, 8};
  write_bytes(dir / "short.tga", tga_header + std::string(31, '\x10'));
  expect_input_error(dir / "short.tga", "TGA declares 4x2 texels, more than its bytes can hold (needs 32, has 31)");
  write_bytes(dir / "exact.tga", tga_header + std::string(32, '\x10'));
  EXPECT_EQ(load_texture(dir / "exact.tga").height(), 2);
  // Run-length: 128 texels in each two-byte packet at most.
  std::string rle{0, 0, 11, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 8, 0};
  rle.replace(12, 4, u16(16384) + u16(16384));
  write_bytes(dir / "huge_rle.tga", rle + std::string(1000, '\xff'));
  expect_input_error(dir / "huge_rle.tga", "run-length TGA declares 16384x16384 texels");

  // A PNG's deflate stream expands at most 1,032-fold: an 8-bit RGBA header of 16384 x 16384 in a small file.
  std::string png = "\x89PNG\r\n\x1a\n";
  const std::string ihdr = "IHDR" + std::string{0, 0, 0x40, 0, 0, 0, 0x40, 0, 8, 6, 0, 0, 0};
  const auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  png += be32(13) + ihdr + be32(static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(ihdr.data()),
                                                                   static_cast<uInt>(ihdr.size()))));
  png += std::string(100'000, '\0');
  write_bytes(dir / "bomb.png", png);
  expect_input_error(dir / "bomb.png", "PNG declares 16384x16384 texels, more than its bytes can hold");
}

}  // namespace
}  // namespace facet::texture_tests
