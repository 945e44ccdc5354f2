// test_lane_helpers.cpp - a lane shader may call helpers that are not inlined and keep lane values in its own structs.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <type_traits>
#include <vector>

#include "facet/draw.hpp"
#include "facet/fragment_lanes.hpp"
#include "support/draw_helpers.hpp"
#include "support/image_asserts.hpp"
#include "support/scenes.hpp"

namespace facet::test {
namespace {

// Lane types go through memory by reference in every ABI, whatever ISA the caller and callee were compiled for.
static_assert(!std::is_trivially_copyable_v<simd::Float> && !std::is_trivially_copyable_v<simd::Int> &&
              !std::is_trivially_copyable_v<simd::UInt>);

// Out of line on purpose: compiled once, for the baseline ISA, and called from the tile loop's AVX-512 and AVX2
// clones. Were the lane types bare 64-byte vectors, the AVX-512 clone would pass them in zmm registers and the
// baseline helper read them from memory: wrong colours or a crash.
[[gnu::noinline]] simd::Float mix_three_to_one(simd::Float a, simd::Float b) { return a * 0.75f + b * 0.25f; }
[[gnu::noinline]] simd::Int odd(simd::UInt primitive) { return simd::to_int(primitive & 1u); }
[[gnu::noinline]] simd::Float add_scalar(simd::Float a, float b) { return a + b; }

// A shader's own struct of lane values, with no alignas: lane types carry their alignment, so a std::vector of it,
// allocated by baseline code, suits the aligned loads of the AVX-512 clone.
struct Tint {
  simd::Float blue;
  simd::Int unused;
};
static_assert(alignof(Tint) == simd::kLaneAlign);

struct HelperShader {
  using Vertex = ColorShader::Vertex;
  using Varyings = ColorShader::Varyings;
  static constexpr bool may_discard = false;
  std::vector<Tint> tints;

  HelperShader() : tints(3) {
    for (int k = 0; k < simd::kLanes; ++k) tints[1].blue[k] = 0.125f;
  }

  VertexOut<Varyings> vertex(const Vertex& v) const { return {v.clip, {v.color}}; }

  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const float r = f.varyings.color.r * 0.75f + f.varyings.color.g * 0.25f;
    const float b = (f.primitive & 1u ? 0.5f : 0.0f) + 0.125f;
    return {r, f.varyings.color.g + 0.0625f, b, 1.0f};
  }

  simd::Color fragment_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    const Vec3 color = f.get(&Varyings::color);
    const Float half = blend(odd(f.primitive) != 0, splat(0.5f), splat(0.0f));
    return {mix_three_to_one(color.x, color.y), add_scalar(color.y, 0.0625f), half + tints[1].blue, splat(1.0f)};
  }
};
static_assert(LaneShader<HelperShader>);

Framebuffer render(const ClipMesh& mesh, bool deferred, int threads) {
  Framebuffer fb(160, 120);
  Renderer renderer(threads);
  renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f), 1.0f);
  const std::vector<ColorShader::Vertex> vertices = color_vertices(mesh);
  RenderState state;
  state.defer_shading = deferred;
  renderer.draw(fb, HelperShader{}, std::span<const ColorShader::Vertex>(vertices), mesh.indices, state);
  renderer.finish(fb);
  return fb;
}

// Immediate shading runs fragment() per pixel; deferred shading runs fragment_lanes, with its out-of-line helpers,
// in whichever clone of the tile loop this CPU takes. Both must draw the same bytes.
TEST(LaneHelpers, OutOfLineHelpersDrawWhatFragmentDraws) {
  const glm::mat4 clip_from_object =
      glm::perspective(glm::radians(50.0f), 4.0f / 3.0f, 0.5f, 10.0f) * glm::translate(glm::mat4(1), {0, 0, -3});
  const ClipMesh sphere = closed_sphere(16, 24, clip_from_object);
  const Framebuffer expected = render(sphere, false, 1);
  for (const int threads : {1, 2}) expect_same(expected, render(sphere, true, threads), "lane shader with helpers");
}

}  // namespace
}  // namespace facet::test
