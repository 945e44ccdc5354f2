// test_setup_cull.cpp - setup's 16-lane culling pass rejects exactly the triangles the full per-triangle setup culls.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "facet/framebuffer.hpp"
#include "setup/setup.hpp"

namespace facet::detail {
namespace {

constexpr int kWidth = 67, kHeight = 45;  // not multiples of the tile size, so the clamps at the far edges matter

struct Soup {
  std::vector<ProjectedVertex> projected;
  std::vector<std::uint32_t> indices;
};

// Triangles from sub-pixel slivers to a few pixels, corners on a coarse sub-pixel grid so that many pixel centres
// fall exactly on edges and corners (the fill rule decides them) and many triangles have zero area, plus some
// large ones and some reaching past the target's edges.
Soup tiny_triangles(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  Soup soup;
  const auto coordinate = [&](int extent, int centre, int reach) {
    std::uniform_int_distribution<int> offset(-reach, reach);
    const int v = centre * kSubpixelScale + offset(rng) * 32;
    return std::clamp(v, -kSubpixelScale, (extent + 1) * kSubpixelScale);
  };
  std::uniform_int_distribution<int> px(-1, kWidth), py(-1, kHeight), size(0, 9);
  for (std::size_t t = 0; t < count; ++t) {
    const int cx = px(rng), cy = py(rng);
    const int reach = size(rng) == 9 ? 400 : 8 * (1 + size(rng) % 4);  // up to 4 pixels, sometimes 50
    for (int k = 0; k < 3; ++k) {
      soup.indices.push_back(static_cast<std::uint32_t>(soup.projected.size()));
      soup.projected.push_back({coordinate(kWidth, cx, reach), coordinate(kHeight, cy, reach), 0.5f, 1.0f, 0});
    }
  }
  return soup;
}

SetupInput input_for(const Soup& soup, CullMode cull, std::size_t first, std::size_t count) {
  const int tiles_x = (kWidth + kTileSize - 1) / kTileSize;
  return {nullptr, soup.projected.data(), 0, nullptr, nullptr, soup.projected.size(), soup.indices, nullptr,
          first, count, kWidth, kHeight, tiles_x, cull, 1.0f};
}

// Whether the full setup of triangle t alone (one triangle never reaches the 16-lane pass) keeps it.
bool setup_keeps(const Soup& soup, CullMode cull, std::size_t t) {
  SetupChunk chunk;
  chunk.reset();
  setup_triangles(input_for(soup, cull, t, 1), chunk);
  return !chunk.triangles.empty();
}

TEST(SetupCull, RejectsExactlyWhatFullSetupCulls) {
  const Soup soup = tiny_triangles(16 * 400, 7);
  for (const CullMode cull : {CullMode::back, CullMode::front, CullMode::none}) {
    std::size_t kept = 0, rejected = 0;
    for (std::size_t first = 0; first < soup.indices.size() / 3; first += kCullLanes) {
      const std::uint32_t keep = setup_cull_lanes(input_for(soup, cull, first, kCullLanes), first);
      for (int i = 0; i < kCullLanes; ++i) {
        const bool lane_keeps = (keep >> i) & 1u;
        ASSERT_EQ(lane_keeps, setup_keeps(soup, cull, first + i))
            << "triangle " << first + i << ", cull mode " << static_cast<int>(cull);
        (lane_keeps ? kept : rejected) += 1;
      }
    }
    // The soup exercises both outcomes in every mode.
    EXPECT_GT(kept, 400u);
    EXPECT_GT(rejected, 400u);
  }
}

TEST(SetupCull, KeepsTrianglesOutsideTheFrustumAndBlocksWithInvalidIndicesForFullSetup) {
  Soup soup = tiny_triangles(16, 3);
  // All three corners outside the same plane: culled, but by the full setup, which also counts clipping.
  for (int k = 0; k < 3; ++k) soup.projected[k].outcode = 1;
  const SetupInput in = input_for(soup, CullMode::back, 0, kCullLanes);
  EXPECT_EQ(setup_cull_lanes(in, 0) & 1u, 1u);
  soup.indices[5] = 1000;  // past the vertices: the whole block goes to full setup, which counts it invalid
  EXPECT_EQ(setup_cull_lanes(input_for(soup, CullMode::back, 0, kCullLanes), 0), 0xffffu);
}

// A whole chunk through setup_triangles (16-lane pass first) gives the same triangles, in the same order, and the
// same counts as setting the triangles up one at a time.
TEST(SetupCull, ChunkSetupMatchesOneTriangleAtATime) {
  Soup soup = tiny_triangles(16 * 64 + 5, 11);  // a tail shorter than 16 takes the per-triangle path
  soup.indices[3 * 40 + 1] = 99999;            // one invalid triangle
  const std::size_t count = soup.indices.size() / 3;
  SetupChunk whole;
  whole.reset();
  setup_triangles(input_for(soup, CullMode::back, 0, count), whole);
  std::vector<std::uint32_t> expected;
  std::size_t culled = 0, invalid = 0;
  for (std::size_t t = 0; t < count; ++t) {
    SetupChunk one;
    one.reset();
    setup_triangles(input_for(soup, CullMode::back, t, 1), one);
    for (const TriangleSetup& s : one.triangles) expected.push_back(s.primitive);
    culled += one.culled;
    invalid += one.invalid;
  }
  std::vector<std::uint32_t> actual;
  for (const TriangleSetup& s : whole.triangles) actual.push_back(s.primitive);
  EXPECT_EQ(actual, expected);
  EXPECT_EQ(whole.culled, culled);
  EXPECT_EQ(whole.invalid, invalid);
  EXPECT_EQ(invalid, 1u);
}

}  // namespace
}  // namespace facet::detail
