// test_deferred_shading.cpp - deferred shading (visibility pass, then one shading pass) draws what immediate does.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <bit>
#include <random>
#include <type_traits>

#include "facet/detail/raster_deferred.hpp"
#include "facet/draw.hpp"
#include "facet/fragment_lanes.hpp"
#include "support/draw_helpers.hpp"
#include "support/image_asserts.hpp"

namespace facet::test {
namespace {

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// A shader whose colour depends on everything a fragment carries: varyings, their derivatives (when kDerivatives),
// window depth, pixel position, primitive index and facing. ProbeShader<true, ...> also has fragment_lanes, the same
// function on 16 lanes, so deferred shading takes its lane path. (It is a derived struct rather than a member with
// `requires kLanes`: a shader that declares fragment_lanes must be able to use it, ShaderTraits says.)
template <bool kDerivatives>
struct ScalarProbeShader {
  using Vertex = ColorShader::Vertex;
  struct Varyings {
    glm::vec3 color;
    float u;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = kDerivatives;

  VertexOut<Varyings> vertex(const Vertex& v) const { return {v.clip, {v.color, v.clip.x * 3.0f}}; }

  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    float r = f.varyings.color.r, g = f.varyings.color.g;
    if constexpr (kDerivatives) {
      r += 40.0f * f.ddx.u;
      g += 40.0f * f.ddy.color.g;
    }
    const float b = 0.5f * f.screen.z + 0.25f * static_cast<float>(f.primitive % 3) + (f.front_facing ? 0.0f : 0.125f) +
                    0.001f * f.screen.x - 0.001f * f.screen.y;
    return {r, g, b, 1.0f};
  }
};

template <bool kDerivatives>
struct LaneProbeShader : ScalarProbeShader<kDerivatives> {
  using typename ScalarProbeShader<kDerivatives>::Varyings;
  simd::Color fragment_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    const Vec3 color = f.get(&Varyings::color);
    Float r = color.x, g = color.y;
    if constexpr (kDerivatives) {
      r += 40.0f * f.ddx[3];
      g += 40.0f * f.ddy[1];
    }
    const Float third = to_float(to_int(f.primitive % 3u));
    const Float b = 0.5f * f.depth + 0.25f * third + blend(f.front_facing, splat(0.0f), splat(0.125f)) +
                    0.001f * f.screen_x - 0.001f * f.screen_y;
    return {r, g, b, splat(1.0f)};
  }
};

template <bool kLanes, bool kDerivatives>
using ProbeShader = std::conditional_t<kLanes, LaneProbeShader<kDerivatives>, ScalarProbeShader<kDerivatives>>;

// The shading pass interpolates the triangles of a strip at the lanes strip_triangle_starts picks: each triangle in
// the strip must have one, and no lane may be picked without a triangle. Strips of 1 to 5 triangles in random
// places (disjoint runs, triangles in one row only, empty lanes) and in the layouts of a mesh's strips, in every
// lane layout, which must all pick the same lanes.
template <class L>
unsigned strip_starts_in(const std::uint32_t* refs) {
  return detail::strip_triangle_starts<L>(simd::load<simd::UIntT<L>>(refs));
}

TEST(StripTriangleStarts, EveryTriangleOfTheStripHasALane) {
  std::mt19937 rng(11);
  int repeated = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    alignas(64) std::uint32_t refs[simd::kLanes];
    const unsigned kinds = 1 + rng() % 5;
    if (trial % 2) {
      for (std::uint32_t& r : refs) r = rng() % (kinds + 1) == 0 ? detail::kNoTriangle : 100 + rng() % kinds;
    } else {  // columns split at a random cut per row, as a mesh's edges cross a strip
      const int cut0 = static_cast<int>(rng() % 9), cut1 = static_cast<int>(rng() % 9);
      for (int k = 0; k < simd::kLanes; ++k) refs[k] = (k & 7) < (k < 8 ? cut0 : cut1) ? 7u : 8u;
    }
    const unsigned starts = strip_starts_in<simd::Whole>(refs);
    ASSERT_EQ(strip_starts_in<simd::Halves>(refs), starts) << "trial " << trial;
    ASSERT_EQ(strip_starts_in<simd::Quarters>(refs), starts) << "trial " << trial;
    for (int k = 0; k < simd::kLanes; ++k) {
      if (refs[k] == detail::kNoTriangle) {
        ASSERT_FALSE(starts >> k & 1u) << "trial " << trial << ": lane " << k << " has no triangle";
        continue;
      }
      int picked = 0;
      for (int j = 0; j < simd::kLanes; ++j) picked += (starts >> j & 1u) && refs[j] == refs[k];
      ASSERT_GE(picked, 1) << "trial " << trial << ": triangle of lane " << k << " has no lane";
      repeated += picked > 1;
    }
  }
  // Repeats only cost time. In the split layouts, what a mesh's edges draw, triangle 8 repeats exactly when its run
  // in row 1 starts left of its run in row 0 (cut1 < cut0).
  EXPECT_GT(repeated, 0);  // the random strips do split triangles
  for (int cut0 = 0; cut0 <= 8; ++cut0)
    for (int cut1 = 0; cut1 <= 8; ++cut1) {
      alignas(64) std::uint32_t refs[simd::kLanes];
      for (int k = 0; k < simd::kLanes; ++k) refs[k] = (k & 7) < (k < 8 ? cut0 : cut1) ? 7u : 8u;
      const unsigned starts = strip_starts_in<simd::Whole>(refs);
      const int kinds = (cut0 > 0 || cut1 > 0) + (cut0 < 8 || cut1 < 8);
      const int repeats = cut1 < cut0 && cut0 < 8;
      EXPECT_EQ(std::popcount(starts), kinds + repeats) << cut0 << " " << cut1;
      EXPECT_EQ(strip_starts_in<simd::Halves>(refs), starts) << cut0 << " " << cut1;
      EXPECT_EQ(strip_starts_in<simd::Quarters>(refs), starts) << cut0 << " " << cut1;
    }
}

#pragma GCC diagnostic pop

static_assert(LaneShader<ProbeShader<true, false>> && LaneShader<ProbeShader<true, true>>);
static_assert(!LaneShader<ProbeShader<false, false>>);
// A lane shader that says nothing about lanes_read_primitive gets primitive and front_facing per lane, as this one
// needs (test_deferred_bench_shader.cpp checks the benchmark shader, which opts out).
static_assert(ShaderTraits<ProbeShader<true, false>>::lanes_read_primitive);

struct Draw {
  ClipMesh mesh;
  RenderState state;
};

template <class S>
Framebuffer render(const std::vector<Draw>& draws, int width, int height, bool deferred, int threads,
                   float clear_depth = 1.0f, int samples = 1) {
  Framebuffer fb(width, height, samples);
  fb.keep_samples(true);
  Renderer renderer(threads);
  renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f), clear_depth);
  const S shader;
  for (const Draw& d : draws) {
    const std::vector<ColorShader::Vertex> vertices = color_vertices(d.mesh);
    RenderState state = d.state;
    state.defer_shading = deferred;
    renderer.draw(fb, shader, std::span<const ColorShader::Vertex>(vertices), d.mesh.indices, state);
  }
  renderer.finish(fb);
  return fb;
}

// Immediate shading with the scalar fragment is the definition; deferred shading must match it bit for bit with
// the scalar fragment (one triangle at a time) and with the lane fragment (all of a strip's triangles at once).
template <bool kDerivatives>
void expect_deferred_matches(const std::vector<Draw>& draws, int width, int height, float clear_depth = 1.0f) {
  const Framebuffer expected = render<ProbeShader<true, kDerivatives>>(draws, width, height, false, 1, clear_depth);
  for (const int threads : {1, 3}) {
    expect_same(expected, render<ProbeShader<false, kDerivatives>>(draws, width, height, true, threads, clear_depth),
                "deferred, scalar fragment");
    expect_same(expected, render<ProbeShader<true, kDerivatives>>(draws, width, height, true, threads, clear_depth),
                "deferred, lane fragment");
  }
}

// With several samples per pixel: the shader runs once per pixel and triangle, at the pixel centre, whichever
// samples that triangle covers. Deferred lane shading shades a strip whose pixels meet several triangles in rounds,
// a triangle per lane each; every lane must get what the scalar fragment computes for that pixel and triangle.
template <bool kDerivatives>
void expect_multisampled_deferred_matches(const std::vector<Draw>& draws, int width, int height, int samples) {
  using Scalar = ProbeShader<false, kDerivatives>;
  using Lanes = ProbeShader<true, kDerivatives>;
  const Framebuffer expected = render<Scalar>(draws, width, height, false, 1, 1.0f, samples);
  for (const int threads : {1, 3}) {
    const Framebuffer scalar = render<Scalar>(draws, width, height, true, threads, 1.0f, samples);
    const Framebuffer lanes = render<Lanes>(draws, width, height, true, threads, 1.0f, samples);
    for (int k = 0; k < samples; ++k) {
      EXPECT_TRUE(std::ranges::equal(scalar.sample_color(k), expected.sample_color(k)))
          << samples << " samples, deferred, scalar fragment: sample " << k;
      EXPECT_TRUE(std::ranges::equal(lanes.sample_color(k), expected.sample_color(k)))
          << samples << " samples, deferred, lane fragment: sample " << k;
    }
    expect_same(expected, scalar, "multisampled, deferred, scalar fragment");
    expect_same(expected, lanes, "multisampled, deferred, lane fragment");
  }
}

glm::mat4 camera(glm::vec3 offset) {
  return glm::perspective(glm::radians(50.0f), 4.0f / 3.0f, 0.5f, 10.0f) * glm::translate(glm::mat4(1), offset);
}

TEST(DeferredShading, DenseSphereMatchesImmediate) {
  // 1 to 30 pixels per triangle: most strips hold several triangles. 203x150 leaves partial tiles and blocks.
  const std::vector<Draw> draws{{closed_sphere(40, 64, camera({0.2f, -0.1f, -3.0f})), RenderState{}}};
  expect_deferred_matches<false>(draws, 203, 150);
  expect_deferred_matches<true>(draws, 203, 150);
}

TEST(DeferredShading, MultisampledDenseMeshesMatchImmediate) {
  RenderState no_cull;
  no_cull.cull = CullMode::none;
  const std::vector<Draw> draws{{closed_sphere(40, 64, camera({0.2f, -0.1f, -3.0f})), RenderState{}},
                                {triangle_soup(60, 7), no_cull}};
  for (const int samples : {2, 4, 8}) {
    expect_multisampled_deferred_matches<false>(draws, 203, 150, samples);
    expect_multisampled_deferred_matches<true>(draws, 203, 150, samples);
  }
}

// A sphere of 30,720 triangles in about 10,000 pixels: most visible triangles' bounds hold at most 2 x 2 pixels,
// and many triangles cover no sample at all. Under LESS, LEQUAL and without depth writes, at every sample count,
// the visibility pass keeps what the immediate path draws.
TEST(DeferredShading, TinyTrianglesMatchImmediate) {
  RenderState less, lequal, no_write;
  lequal.depth_func = DepthFunc::lequal;
  no_write.depth_write = false;
  for (const RenderState& state : {less, lequal, no_write}) {
    RenderState no_cull = state;
    no_cull.cull = CullMode::none;  // back faces too, drawn first or hidden
    const std::vector<Draw> draws{{closed_sphere(120, 128, camera({0.1f, -0.05f, -3.0f})), no_cull}};
    expect_deferred_matches<true>(draws, 203, 150);
    for (const int samples : {2, 4, 8}) expect_multisampled_deferred_matches<true>(draws, 203, 150, samples);
  }
}

TEST(DeferredShading, SeveralDrawsAndDepthFunctionsMatchImmediate) {
  RenderState no_cull;
  no_cull.cull = CullMode::none;  // back faces show: front_facing varies
  RenderState lequal = no_cull;
  lequal.depth_func = DepthFunc::lequal;
  RenderState no_write = no_cull;
  no_write.depth_write = false;
  const std::vector<Draw> draws{{closed_sphere(12, 16, camera({-0.4f, 0.0f, -2.5f})), no_cull},
                                {triangle_soup(60, 7), lequal},
                                {jittered_grid(9, 7, 3, true), no_write},
                                {closed_sphere(20, 24, camera({0.5f, 0.3f, -3.5f})), lequal}};
  expect_deferred_matches<true>(draws, 190, 133);

  // Reversed depth: cleared to 0, GREATER keeps the farthest.
  std::vector<Draw> reversed = draws;
  for (Draw& d : reversed) d.state.depth_func = DepthFunc::greater;
  expect_deferred_matches<false>(reversed, 190, 133, 0.0f);
}

// Every depth function, where the visibility pass tests LESS and LEQUAL as constants and the others by which
// comparisons pass: a sphere drawn with LESS, then a soup and the same sphere again in other colours (where EQUAL
// passes) with the function under test (GREATER and GEQUAL pass where the soup lies behind the sphere), with and
// without depth writes.
TEST(DeferredShading, EveryDepthFunctionMatchesImmediate) {
  for (const DepthFunc func : {DepthFunc::never, DepthFunc::less, DepthFunc::equal, DepthFunc::lequal,
                               DepthFunc::greater, DepthFunc::notequal, DepthFunc::gequal, DepthFunc::always})
    for (const bool write : {true, false}) {
      RenderState first;  // front faces only, so that the sphere drawn again meets its own depths
      RenderState tested = first;
      tested.depth_func = func;
      tested.depth_write = write;
      RenderState soup = tested;
      soup.cull = CullMode::none;
      const ClipMesh sphere = closed_sphere(16, 20, camera({0.1f, 0.0f, -3.0f}));
      ClipMesh again = sphere;  // the same depths in other colours, so that what EQUAL lets through shows
      for (glm::vec3& c : again.color) c = glm::vec3(1.0f) - c;
      const std::vector<Draw> draws{{sphere, first}, {triangle_soup(40, 5), soup}, {again, tested}};
      SCOPED_TRACE(::testing::Message() << "depth function " << static_cast<int>(func) << (write ? "" : ", no writes"));
      expect_deferred_matches<true>(draws, 150, 110);
    }
}

// Draws with colour writes off change depth alone, and the pipeline skips their shading: a soup drawn into depth
// first (onto the pending clear) hides the sphere behind it, then a depth-only sphere under LEQUAL and one without
// depth writes change nothing, and the colour the soup did not draw keeps the clear colour, as drawn immediately.
TEST(DeferredShading, DepthOnlyDrawsMatchImmediate) {
  RenderState depth_only;
  depth_only.cull = CullMode::none;
  depth_only.color_write = false;
  RenderState depth_only_lequal = depth_only;
  depth_only_lequal.depth_func = DepthFunc::lequal;
  RenderState no_writes = depth_only;
  no_writes.depth_write = false;
  const ClipMesh sphere = closed_sphere(16, 20, camera({0.1f, 0.0f, -3.0f}));
  const std::vector<Draw> draws{{triangle_soup(40, 5), depth_only},
                                {sphere, RenderState{}},
                                {closed_sphere(12, 16, camera({-0.3f, 0.1f, -2.5f})), depth_only_lequal},
                                {triangle_soup(20, 9), no_writes}};
  expect_deferred_matches<true>(draws, 150, 110);
}

// The visibility pass takes a huge triangle's edge values per block in 64 bits, and a smaller one's in 32 bits from
// its corner (kSmallTriangleSpan): 1300 pixels wide, the soup has triangles of both kinds, some of the smaller kind
// close to the span limit, and the sphere small ones.
TEST(DeferredShading, HugeAndSmallTrianglesMatchImmediate) {
  constexpr int kWidth = 1300, kHeight = 72;
  RenderState no_cull;
  no_cull.cull = CullMode::none;
  const std::vector<Draw> draws{{triangle_soup(40, 13), no_cull},
                                {closed_sphere(24, 32, camera({0.1f, 0.0f, -3.0f})), RenderState{}}};
  int huge = 0, large = 0;
  const ClipMesh& soup = draws[0].mesh;
  for (std::size_t t = 0; t + 2 < soup.indices.size(); t += 3) {
    float lo = kWidth, hi = 0.0f;
    bool in_front = true;
    for (int k = 0; k < 3; ++k) {
      const glm::vec4& c = soup.clip[soup.indices[t + k]];
      in_front &= c.w > 0.0f;
      const float x = std::clamp((c.x / c.w + 1.0f) * 0.5f * kWidth, 0.0f, float(kWidth));
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    huge += in_front && hi - lo > detail::kSmallTriangleSpan + 8;
    large += in_front && hi - lo > 512 && hi - lo < detail::kSmallTriangleSpan - 8;  // 32 bits, near its budget
  }
  ASSERT_GE(huge, 3);
  ASSERT_GE(large, 3);
  expect_deferred_matches<false>(draws, kWidth, kHeight);
}

TEST(DeferredShading, WithoutDepthTestTheLastDrawnTriangleWins) {
  RenderState painter = no_depth_no_cull();
  const std::vector<Draw> draws{{triangle_soup(80, 11), painter}, {jittered_grid(5, 4, 9, false), painter}};
  expect_deferred_matches<true>(draws, 160, 120);
}

}  // namespace
}  // namespace facet::test
