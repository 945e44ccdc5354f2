// test_multisample.cpp - multisampling: per-sample coverage against an oracle, exactly-once tiling, resolve, threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <stdexcept>
#include <vector>

#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

// Vulkan's standard sample locations, in 1/16 pixel from the pixel's top-left corner, as the specification lists
// them (written out here again rather than taken from the renderer, as an oracle's should be).
std::vector<glm::ivec2> standard_locations(int samples) {
  switch (samples) {
    case 2: return {{12, 12}, {4, 4}};
    case 4: return {{6, 2}, {14, 6}, {2, 10}, {10, 14}};
    case 8: return {{9, 5}, {7, 11}, {13, 9}, {5, 3}, {3, 13}, {1, 7}, {11, 15}, {15, 1}};
    default: return {{8, 8}};
  }
}

// A triangle of one flat colour per triangle, the colour encoding its index, in clip space with w = 1.
glm::vec3 index_color(std::uint32_t t) {
  return glm::vec3(static_cast<float>(t & 0xff), static_cast<float>((t >> 8) & 0xff), 77.0f) / 255.0f;
}
std::uint32_t index_pixel(std::uint32_t t) { return pack_rgba8(glm::vec4(index_color(t), 1.0f)); }

void add_flat_triangle(ClipMesh& m, const glm::vec2 (&screen)[3], int width, int height) {
  const auto t = static_cast<std::uint32_t>(m.indices.size() / 3);
  for (const glm::vec2& p : screen) {
    m.clip.emplace_back(2.0f * p.x / static_cast<float>(width) - 1.0f, 1.0f - 2.0f * p.y / static_cast<float>(height),
                        0.0f, 1.0f);
    m.color.push_back(index_color(t));
    m.indices.push_back(static_cast<std::uint32_t>(m.clip.size() - 1));
  }
}

// Per sample plane and pixel, the last triangle of `m` (all inside the target, w = 1) that covers the sample, by the
// definition: the edge functions of the snapped corners in 64-bit integers at the sample's position, with the
// top-left rule; -1 where none does.
std::vector<std::vector<int>> sample_owners(const ClipMesh& m, int width, int height, int samples) {
  const std::vector<glm::ivec2> at = standard_locations(samples);
  std::vector<std::vector<int>> owner(static_cast<std::size_t>(samples),
                                      std::vector<int>(static_cast<std::size_t>(width) * height, -1));
  for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
    std::int64_t x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec4& c = m.clip[m.indices[3 * t + k]];
      // The reference rasterizer's snapping: the same float arithmetic as setup.
      const float sx = (c.x + 1.0f) * 0.5f * static_cast<float>(width);
      const float sy = (1.0f - c.y) * 0.5f * static_cast<float>(height);
      x[k] = std::lrint(sx * 256.0f), y[k] = std::lrint(sy * 256.0f);
    }
    const std::int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0) continue;
    if (area < 0) std::swap(x[1], x[2]), std::swap(y[1], y[2]);
    for (int py = 0; py < height; ++py)
      for (int px = 0; px < width; ++px)
        for (int s = 0; s < samples; ++s) {
          const std::int64_t sx = 256 * std::int64_t{px} + 16 * at[s].x, sy = 256 * std::int64_t{py} + 16 * at[s].y;
          bool inside = true;
          for (int k = 0; k < 3; ++k) {
            const int a = k, b = (k + 1) % 3;
            const std::int64_t dx = x[b] - x[a], dy = y[b] - y[a];
            const std::int64_t e = dx * (sy - y[a]) - dy * (sx - x[a]);
            inside &= e > 0 || (e == 0 && ((dy == 0 && dx > 0) || dy < 0));
          }
          if (inside) owner[s][static_cast<std::size_t>(py) * width + px] = static_cast<int>(t);
        }
  }
  return owner;
}

Framebuffer draw_samples(const ClipMesh& m, int width, int height, int samples, RenderState state, int threads = 2,
                         bool keep = true) {
  Framebuffer fb(width, height, samples);
  fb.keep_samples(keep);
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  Renderer renderer(threads);
  renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(vertices), m.indices, state);
  renderer.finish(fb);
  return fb;
}

// Random triangles from sub-pixel slivers (which may cover samples but no pixel centre) to large ones.
ClipMesh random_triangles(int count, int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> px(1.0f, static_cast<float>(width) - 1.0f),
      py(1.0f, static_cast<float>(height) - 1.0f), unit(-1.0f, 1.0f);
  ClipMesh m;
  for (int t = 0; t < count; ++t) {
    const float size = t % 3 == 0 ? 0.7f : (t % 3 == 1 ? 4.0f : 30.0f);
    const glm::vec2 c(px(rng), py(rng));
    glm::vec2 corner[3];
    for (glm::vec2& p : corner)
      p = glm::clamp(c + size * glm::vec2(unit(rng), unit(rng)), glm::vec2(0.0f),
                     glm::vec2(static_cast<float>(width), static_cast<float>(height)));
    add_flat_triangle(m, corner, width, height);
  }
  return m;
}

// `count` triangles whose other corners lie within `reach` pixels either way of their first, anywhere in the target.
ClipMesh small_triangles(int count, int width, int height, std::uint32_t seed, float reach) {
  ClipMesh m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> px(1.0f, width - 1.0f), py(1.0f, height - 1.0f), unit(-reach, reach);
  for (int t = 0; t < count; ++t) {
    const glm::vec2 c(px(rng), py(rng));
    glm::vec2 corner[3] = {c, c + glm::vec2(unit(rng), unit(rng)), c + glm::vec2(unit(rng), unit(rng))};
    add_flat_triangle(m, corner, width, height);
  }
  return m;
}

TEST(Multisample, EverySampleHasTheTriangleThatCoversItLast) {
  const int width = 150, height = 90;  // 3 x 2 tiles, cut short
  const ClipMesh m = random_triangles(400, width, height, 7);
  for (const int samples : {2, 4, 8}) {
    const std::vector<std::vector<int>> owner = sample_owners(m, width, height, samples);
    for (const bool deferred : {true, false}) {
      RenderState state = no_depth_no_cull();
      state.defer_shading = deferred;
      const Framebuffer fb = draw_samples(m, width, height, samples, state);
      int mismatches = 0, covered = 0;
      for (int s = 0; s < samples; ++s) {
        const std::span<const std::uint32_t> plane = fb.sample_color(s);
        for (std::size_t i = 0; i < plane.size(); ++i) {
          const int t = owner[s][i];
          const std::uint32_t expected = t < 0 ? pack_rgba8(glm::vec4(0, 0, 0, 1)) : index_pixel(t);
          covered += t >= 0;
          if (plane[i] != expected && ++mismatches <= 5)
            ADD_FAILURE() << samples << " samples" << (deferred ? " (deferred)" : "") << ": sample " << s
                          << " of pixel " << i % width << ", " << i / width << " is " << std::hex << plane[i]
                          << ", expected triangle " << std::dec << t;
        }
      }
      EXPECT_EQ(mismatches, 0);
      EXPECT_GT(covered, samples * width * height / 2) << "the triangles cover most samples";
    }
  }
}

// A jittered grid tiling the target, white at half opacity over black: a sample covered once is 127 or 128
// (interpolated white may fall a rounding error short of 1), twice 191, never 0. Blending is drawn immediately, so this is the immediate path's count; the deferred path keeps one
// triangle per sample by construction, and the oracle test above checks which.
TEST(Multisample, TilingTrianglesCoverEverySampleExactlyOnce) {
  const int width = 130, height = 70;
  ClipMesh m = jittered_grid(23, 17, 3, false);
  for (glm::vec3& c : m.color) c = glm::vec3(1.0f);
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  for (const int samples : {2, 4, 8}) {
    RenderState state = no_depth_no_cull();
    state.blend = BlendMode::alpha;
    Framebuffer fb(width, height, samples);
    fb.keep_samples(true);
    Renderer renderer(2);
    renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    renderer.draw(fb, TranslucentShader{}, std::span<const TranslucentShader::Vertex>(vertices), m.indices, state);
    renderer.finish(fb);
    for (int s = 0; s < samples; ++s) {
      const std::span<const std::uint32_t> plane = fb.sample_color(s);
      for (std::size_t i = 0; i < plane.size(); ++i)
        ASSERT_NEAR(static_cast<int>(plane[i] & 0xffu), 128, 1) << samples << " samples: sample " << s << " of pixel " << i % width << ", "
                                         << i / width << " (0: left out, 191: covered twice)";
    }
  }
}

// An edge through a pixel's centre covers half of it: the resolved pixel is within 1/N of half white.
TEST(Multisample, HalfCoveredPixelsResolveToTheirCoverage) {
  const int size = 64;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
  for (const int samples : {2, 4, 8})
    for (const bool deferred : {true, false})
      for (int trial = 0; trial < 60; ++trial) {
        const float a = angle(rng);
        const glm::vec2 centre(32.5f, 32.5f), along(std::cos(a), std::sin(a)), side(-along.y, along.x);
        ClipMesh m;
        const glm::vec2 corner[3] = {centre - 20.0f * along, centre + 20.0f * along, centre + 20.0f * side};
        add_flat_triangle(m, corner, size, size);
        m.color.assign(3, glm::vec3(1.0f));
        RenderState state = no_depth_no_cull();
        state.defer_shading = deferred;
        const Framebuffer fb = draw_samples(m, size, size, samples, state);
        const float value = static_cast<float>(fb.pixel(32, 32) & 0xffu) / 255.0f;
        EXPECT_NEAR(value, 0.5f, 1.0f / static_cast<float>(samples) + 1.0f / 255.0f)
            << samples << " samples, edge at " << a << " rad" << (deferred ? " (deferred)" : "");
        // Far inside and far outside the triangle, all samples or none.
        const glm::ivec2 in = glm::ivec2(centre + 8.0f * side), out = glm::ivec2(centre - 8.0f * side);
        EXPECT_EQ(fb.pixel(in.x, in.y), 0xffffffffu);
        EXPECT_EQ(fb.pixel(out.x, out.y), pack_rgba8(glm::vec4(0, 0, 0, 1)));
      }
}

// Depth-tested overlapping geometry: every sample plane and the resolve are the same at any thread count, and the
// same drawn immediately or deferred (two different hierarchical-depth walks).
TEST(Multisample, SameImageAtAnyThreadCountAndEitherShading) {
  const int width = 200, height = 140;
  ClipMesh m = triangle_soup(300, 5);
  RenderState state;
  state.cull = CullMode::none;
  for (const int samples : {4, 8}) {
    const Framebuffer base = draw_samples(m, width, height, samples, state, 1);
    for (const int threads : {2, 3}) {
      for (const bool deferred : {true, false}) {
        RenderState s = state;
        s.defer_shading = deferred;
        const Framebuffer fb = draw_samples(m, width, height, samples, s, threads);
        for (int k = 0; k < samples; ++k) {
          ASSERT_TRUE(std::ranges::equal(fb.sample_color(k), base.sample_color(k)))
              << samples << " samples, " << threads << " threads" << (deferred ? ", deferred" : "") << ": sample " << k;
        }
        ASSERT_TRUE(std::ranges::equal(fb.color(), base.color()));
        ASSERT_TRUE(std::ranges::equal(fb.depth(), base.depth()));
      }
    }
  }
}

// A frame whose recorded work passes the renderer's limit is drawn in several tile passes, multisampled targets
// keeping their samples in between: the image is the one a single tile pass draws, bit for bit. Several draws
// (a limit of 0 draws each before the next), and one draw of two batches drawn in the painter's order (its
// varyings, shaded once for the whole draw, stay recorded across the parts). At 1 sample the default limit is
// kCachedRecordedBytes, so there the frame drawn whole is itself in two parts, cut elsewhere.
TEST(Multisample, FramesDrawnInPartsMatchOneTilePass) {
  const int width = 90, height = 70;
  const ClipMesh soup = random_triangles(600, width, height, 21);
  // Small triangles, more than two batches of 65,536: the draw is cut in two.
  const ClipMesh dense = small_triangles(140000, width, height, 22, 1.5f);
  const std::vector<ColorShader::Vertex> soup_vertices = color_vertices(soup), dense_vertices = color_vertices(dense);
  const auto draw = [&](int samples, std::size_t limit, bool keep) {
    Framebuffer fb(width, height, samples);
    fb.keep_samples(keep);
    Renderer renderer(2);
    renderer.set_recorded_bytes_limit(limit);
    renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    RenderState state;
    state.cull = CullMode::none;
    const std::span<const std::uint32_t> indices(soup.indices);
    for (std::size_t first = 0; first < indices.size(); first += 300)
      renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(soup_vertices),
                    indices.subspan(first, 300), state);
    RenderState painter = no_depth_no_cull();
    painter.order = DrawOrder::back_to_front;
    renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(dense_vertices), dense.indices, painter);
    renderer.finish(fb);
    return fb;
  };
  for (const int samples : {1, 4}) {
    const Framebuffer whole = draw(samples, Renderer::kDefaultRecordedBytes, false);
    const Framebuffer parts = draw(samples, 0, false);
    EXPECT_EQ(parts.keeps_samples(), false);
    EXPECT_TRUE(std::ranges::equal(parts.color(), whole.color())) << samples << " samples";
    EXPECT_TRUE(std::ranges::equal(parts.depth(), whole.depth())) << samples << " samples";
    if (samples > 1) {
      EXPECT_NO_THROW((void)parts.sample_color(samples - 1));  // held for the parts
      EXPECT_THROW((void)whole.sample_color(0), std::logic_error);
    }
  }
}

// A draw whose set-up work would outweigh a large target's sample planes (200,000 triangles, 27 MB of set-up work,
// against 25 MB of planes at 1024x768 and 4 samples) takes the planes before it is set up and goes on in cached
// parts; a small target's draw records whole. Either way the image is the one a target holding its planes from the
// start draws, at any thread count.
TEST(Multisample, DrawsOutweighingLargeTargetsPlanesTakeThemFirst) {
  const auto dense = [](int width, int height) { return small_triangles(200000, width, height, 31, 2.0f); };
  const auto draw = [](const ClipMesh& m, int width, int height, bool keep, int threads) {
    Framebuffer fb(width, height, 4);
    fb.keep_samples(keep);
    const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
    Renderer renderer(threads);
    renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    RenderState state;
    state.cull = CullMode::none;
    renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(vertices), m.indices, state);
    renderer.finish(fb);
    return fb;
  };
  const ClipMesh large = dense(1024, 768);
  const Framebuffer taken = draw(large, 1024, 768, false, 2);
  EXPECT_NO_THROW((void)taken.sample_color(3));  // the planes were taken
  for (const int threads : {1, 3}) {
    const Framebuffer held = draw(large, 1024, 768, true, threads);
    EXPECT_TRUE(std::ranges::equal(taken.color(), held.color())) << threads << " threads";
    EXPECT_TRUE(std::ranges::equal(taken.depth(), held.depth())) << threads << " threads";
  }
  const ClipMesh small = dense(256, 192);
  const Framebuffer recorded = draw(small, 256, 192, false, 2);
  EXPECT_THROW((void)recorded.sample_color(0), std::logic_error);  // 1.5 MB of planes: recorded whole
  EXPECT_TRUE(std::ranges::equal(recorded.color(), draw(small, 256, 192, true, 2).color()));
}

// The resolve is the rounded mean of a pixel's samples, per channel.
TEST(Multisample, ResolveAveragesSamples) {
  const int width = 70, height = 50;
  const ClipMesh m = random_triangles(60, width, height, 9);
  for (const int samples : {2, 4, 8}) {
    const Framebuffer fb = draw_samples(m, width, height, samples, no_depth_no_cull());
    for (std::size_t i = 0; i < fb.color().size(); ++i)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int s = 0; s < samples; ++s) sum += static_cast<int>((fb.sample_color(s)[i] >> (8 * c)) & 0xffu);
        ASSERT_EQ(static_cast<int>((fb.color()[i] >> (8 * c)) & 0xffu), (sum + samples / 2) / samples);
      }
  }
}

// Samples live in tile memory while the frame is drawn: keeping them afterwards changes what can be read, not the
// image.
TEST(Multisample, KeptSamplesLeaveTheImageAsItIs) {
  const ClipMesh m = random_triangles(150, 61, 37, 7);
  for (const int samples : {2, 4, 8}) {
    for (const bool depth : {false, true}) {
      RenderState state = no_depth_no_cull();
      state.depth_test = depth;
      const Framebuffer kept = draw_samples(m, 61, 37, samples, state, 2, true);
      const Framebuffer bare = draw_samples(m, 61, 37, samples, state, 2, false);
      EXPECT_TRUE(std::ranges::equal(kept.color(), bare.color())) << samples << " samples";
      EXPECT_TRUE(std::ranges::equal(kept.depth(), bare.depth())) << samples << " samples";
      EXPECT_THROW((void)bare.sample_color(0), std::logic_error);
      EXPECT_EQ(kept.sample_color(samples - 1).size(), 61u * 37u);
      EXPECT_THROW((void)kept.sample_color(samples), std::out_of_range);
    }
  }
}

TEST(Multisample, FramebufferRefusesOtherSampleCounts) {
  for (const int samples : {0, 3, 5, 16, -4}) EXPECT_THROW(Framebuffer(8, 8, samples), std::invalid_argument);
  const Framebuffer fb(10, 6, 4);
  EXPECT_EQ(fb.samples(), 4);
  EXPECT_EQ(fb.color().size(), 60u);
  EXPECT_EQ(fb.depth().size(), 60u);
}

}  // namespace
}  // namespace facet::test
