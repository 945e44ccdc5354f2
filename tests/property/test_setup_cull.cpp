// test_setup_cull.cpp - setup's 16-lane culling pass rejects exactly the triangles the full per-triangle setup culls.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "facet/detail/multisample.hpp"
#include "facet/framebuffer.hpp"
#include "core/setup/setup.hpp"

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

SetupInput input_for(const Soup& soup, CullMode cull, std::size_t first, std::size_t count, int samples = 1) {
  const int tiles_x = (kWidth + kTileSize - 1) / kTileSize;
  return {nullptr,
          soup.projected.data(),
          0,
          nullptr,
          nullptr,
          soup.projected.size(),
          soup.indices,
          nullptr,
          first,
          count,
          kWidth,
          kHeight,
          tiles_x,
          cull,
          1.0f,
          samples};
}

CullLanes cull_lanes(const SetupInput& in, std::size_t first) {
  CullLanes lanes;
  setup_cull_lanes(in, first, lanes);
  return lanes;
}

// The full setup of triangle t alone (one triangle never reaches the 16-lane pass).
// One triangle set up on its own, in a chunk reused from call to call (a new chunk reserves room for thousands of
// triangles, which made this test spend most of its time allocating). Valid until the next call.
const SetupChunk& set_up_alone(const Soup& soup, CullMode cull, std::size_t t, int samples = 1) {
  static SetupChunk chunk;
  chunk.reset();
  setup_triangles(input_for(soup, cull, t, 1, samples), chunk);
  return chunk;
}

void expect_same_setup(const TriangleSetup& a, const TriangleSetup& b) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.edge[k].a, b.edge[k].a);
    EXPECT_EQ(a.edge[k].b, b.edge[k].b);
    EXPECT_EQ(a.edge[k].q, b.edge[k].q);
    EXPECT_EQ(a.vertex[k], b.vertex[k]);
  }
  EXPECT_EQ(a.min_x, b.min_x);
  EXPECT_EQ(a.min_y, b.min_y);
  EXPECT_EQ(a.max_x, b.max_x);
  EXPECT_EQ(a.max_y, b.max_y);
  EXPECT_EQ(a.origin_x, b.origin_x);
  EXPECT_EQ(a.origin_y, b.origin_y);
  for (const auto plane :
       {&TriangleSetup::depth, &TriangleSetup::inv_w, &TriangleSetup::b1_over_w, &TriangleSetup::b2_over_w}) {
    EXPECT_EQ((a.*plane).at_origin, (b.*plane).at_origin);
    EXPECT_EQ((a.*plane).ddx, (b.*plane).ddx);
    EXPECT_EQ((a.*plane).ddy, (b.*plane).ddy);
  }
  EXPECT_EQ(a.primitive, b.primitive);
  EXPECT_EQ(a.front_facing, b.front_facing);
}

// With several samples per pixel, bounds grow to the pixels any sample may lie in, and a small triangle is culled
// only when it covers none of their samples.
// The coverage test is one function at every width: culling's 32 bits, setup's 64, and the edge that raster steps
// across pixels (a * i + b * j + q >= 0, make_edge) decide every pixel centre alike, corners on a coarse grid so
// that many centres lie on edges, where the fill rule decides.
TEST(CoverageTest, OneEdgeFunctionAtEveryWidthAndInRastersForm) {
  std::mt19937 rng(41);
  std::uniform_int_distribution<std::int32_t> corner(0, 24 * 32);  // 24 pixels on an 1/8-pixel grid
  int inside = 0, outside = 0;
  for (int n = 0; n < 20000; ++n) {
    const std::int32_t xa = corner(rng) * 8, ya = corner(rng) * 8, xb = corner(rng) * 8, yb = corner(rng) * 8;
    const std::int32_t dx = xb - xa, dy = yb - ya;
    const Edge edge = make_edge(dx, dy, xa, ya);
    const std::int32_t i = corner(rng) / 32, j = corner(rng) / 32;
    const std::int32_t cx = i * kSubpixelScale + kSubpixelScale / 2, cy = j * kSubpixelScale + kSubpixelScale / 2;
    const bool wide = edge_function<std::int64_t>(dx, dy, xa, ya, cx, cy) >= 0;
    ASSERT_EQ(edge_function<std::int32_t>(dx, dy, xa, ya, cx, cy) >= 0, wide) << n;
    ASSERT_EQ(std::int64_t{edge.a} * i + std::int64_t{edge.b} * j + edge.q >= 0, wide) << n;
    (wide ? inside : outside)++;
  }
  EXPECT_GT(inside, 5000);
  EXPECT_GT(outside, 5000);
}

TEST(SetupCull, RejectsExactlyWhatFullSetupCulls) {
  const Soup soup = tiny_triangles(16 * 400, 7);
  for (const int samples : {1, 2, 4, 8})
    for (const CullMode cull : {CullMode::back, CullMode::front, CullMode::none}) {
      std::size_t kept = 0, rejected = 0;
      for (std::size_t first = 0; first < soup.indices.size() / 3; first += kCullLanes) {
        const CullLanes lanes = cull_lanes(input_for(soup, cull, first, kCullLanes, samples), first);
        for (int i = 0; i < kCullLanes; ++i) {
          const bool lane_keeps = (lanes.keep >> i) & 1u;
          const SetupChunk& alone = set_up_alone(soup, cull, first + i, samples);
          ASSERT_EQ(lane_keeps, !alone.triangles.empty())
              << "triangle " << first + i << ", cull mode " << static_cast<int>(cull) << ", " << samples << " samples";
          // Every corner is inside, so whatever the pass keeps it has fully accepted, with setup's bounds.
          ASSERT_EQ(lane_keeps, ((lanes.accepted >> i) & 1u) != 0);
          if (lane_keeps) {
            const TriangleSetup& t = alone.triangles.front();
            EXPECT_EQ(lanes.px0[i], t.min_x);
            EXPECT_EQ(lanes.py0[i], t.min_y);
            EXPECT_EQ(lanes.px1[i], t.max_x);
            EXPECT_EQ(lanes.py1[i], t.max_y);
            if (samples > 1) {
              EXPECT_EQ(lanes.bounds_fraction[i], t.bounds_fraction);
            }
            EXPECT_EQ(lanes.front[i] != 0, t.front_facing);
          }
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
  const CullLanes outside = cull_lanes(input_for(soup, CullMode::back, 0, kCullLanes), 0);
  EXPECT_EQ(outside.keep & 1u, 1u);
  EXPECT_EQ(outside.accepted & 1u, 0u);
  soup.indices[5] = 1000;  // past the vertices: the whole block goes to full setup, which counts it invalid
  const CullLanes invalid = cull_lanes(input_for(soup, CullMode::back, 0, kCullLanes), 0);
  EXPECT_EQ(invalid.keep, 0xffffu);
  EXPECT_EQ(invalid.accepted, 0u);
}

// Blocks of 16 triangles that all face away, as on a closed mesh's far side: the pass answers from facing alone,
// accepts none and keeps only those with a corner outside the frustum, for full setup. Culling front faces or
// nothing, the same triangles take the whole pass, which agrees with full setup.
TEST(SetupCull, BlocksThatAllFaceAwayKeepOnlyTrianglesOutsideTheFrustum) {
  Soup soup = tiny_triangles(16 * 40, 19);
  const std::size_t count = soup.indices.size() / 3;
  for (std::size_t t = 0; t < count; ++t) {
    const ProjectedVertex &a = soup.projected[soup.indices[3 * t]], &b = soup.projected[soup.indices[3 * t + 1]],
                          &c = soup.projected[soup.indices[3 * t + 2]];
    const std::int64_t area = std::int64_t{b.x - a.x} * (c.y - a.y) - std::int64_t{c.x - a.x} * (b.y - a.y);
    if (area < 0) std::swap(soup.indices[3 * t + 1], soup.indices[3 * t + 2]);  // front-facing on screen: flip it
  }
  for (std::size_t t = 3; t < count; t += 7) soup.projected[soup.indices[3 * t + 1]].outcode = 1;
  std::size_t accepted_elsewhere = 0;
  for (std::size_t first = 0; first < count; first += kCullLanes) {
    std::uint32_t outside = 0;
    for (int i = 0; i < kCullLanes; ++i)
      for (int k = 0; k < 3; ++k)
        outside |= static_cast<std::uint32_t>(soup.projected[soup.indices[3 * (first + i) + k]].outcode != 0) << i;
    const CullLanes back = cull_lanes(input_for(soup, CullMode::back, first, kCullLanes), first);
    EXPECT_EQ(back.accepted, 0u) << "block " << first;
    EXPECT_EQ(back.keep, outside) << "block " << first;
    for (const CullMode cull : {CullMode::back, CullMode::front, CullMode::none}) {
      const CullLanes lanes = cull_lanes(input_for(soup, cull, first, kCullLanes), first);
      accepted_elsewhere += static_cast<std::size_t>(std::popcount(lanes.accepted));
      for (int i = 0; i < kCullLanes; ++i) {
        if ((outside >> i) & 1u) continue;  // full setup would clip it, which this soup has no clip positions for
        ASSERT_EQ(((lanes.keep >> i) & 1u) != 0, !set_up_alone(soup, cull, first + i).triangles.empty())
            << "triangle " << first + i << ", cull mode " << static_cast<int>(cull);
      }
    }
  }
  EXPECT_GT(accepted_elsewhere, 100u);  // culling front faces or none, the far side is drawn
}

// Multisampled, each sample's view of a triangle (at_sample) is bounded by exactly the pixels whose sample lies
// within the snapped corners' extremes, clamped to the target: often a pixel less each way than the triangle's
// bounds, which hold those of every sample.
TEST(SetupCull, EachSampleViewHasItsOwnBounds) {
  const Soup soup = tiny_triangles(16 * 100, 5);
  const auto ceil_div = [](std::int32_t v) { return -((-v) >> kSubpixelBits); };
  for (const int samples : {2, 4, 8}) {
    const SamplePattern& pattern = sample_pattern(samples);
    int tighter = 0;
    for (std::size_t t = 0; t < soup.indices.size() / 3; ++t) {
      const SetupChunk& alone = set_up_alone(soup, CullMode::none, t, samples);
      if (alone.triangles.empty()) continue;
      const TriangleSetup& tri = alone.triangles.front();
      std::int32_t min_x = INT32_MAX, min_y = INT32_MAX, max_x = INT32_MIN, max_y = INT32_MIN;
      for (int k = 0; k < 3; ++k) {
        const ProjectedVertex& v = soup.projected[soup.indices[3 * t + k]];
        min_x = std::min(min_x, v.x), max_x = std::max(max_x, v.x);
        min_y = std::min(min_y, v.y), max_y = std::max(max_y, v.y);
      }
      for (int s = 0; s < samples; ++s) {
        const TriangleSetup view = at_sample(tri, pattern, s);
        const std::int32_t x = pattern.offset[s].x + kSubpixelScale / 2, y = pattern.offset[s].y + kSubpixelScale / 2;
        ASSERT_EQ(view.min_x, std::max(0, ceil_div(min_x - x))) << "triangle " << t << ", sample " << s;
        ASSERT_EQ(view.min_y, std::max(0, ceil_div(min_y - y))) << "triangle " << t << ", sample " << s;
        ASSERT_EQ(view.max_x, std::min(kWidth - 1, (max_x - x) >> kSubpixelBits)) << "triangle " << t;
        ASSERT_EQ(view.max_y, std::min(kHeight - 1, (max_y - y) >> kSubpixelBits)) << "triangle " << t;
        tighter += view.min_x > tri.min_x || view.max_x < tri.max_x || view.min_y > tri.min_y || view.max_y < tri.max_y;
      }
    }
    EXPECT_GT(tighter, 100) << samples << " samples";
  }
}

// A whole chunk through setup_triangles (16-lane pass first) gives the same set-up triangles, field for field, in
// the same order, and the same counts as setting the triangles up one at a time, with one sample or several.
TEST(SetupCull, ChunkSetupMatchesOneTriangleAtATime) {
  Soup soup = tiny_triangles(16 * 64 + 5, 11);  // a tail shorter than 16 takes the per-triangle path
  soup.indices[3 * 40 + 1] = 99999;             // one invalid triangle
  const std::size_t count = soup.indices.size() / 3;
  for (const int samples : {1, 4}) {
    SetupChunk whole;
    whole.reset();
    setup_triangles(input_for(soup, CullMode::back, 0, count, samples), whole);
    std::vector<TriangleSetup> expected;
    std::size_t culled = 0, invalid = 0;
    for (std::size_t t = 0; t < count; ++t) {
      const SetupChunk& one = set_up_alone(soup, CullMode::back, t, samples);
      expected.insert(expected.end(), one.triangles.begin(), one.triangles.end());
      culled += one.culled;
      invalid += one.invalid;
    }
    ASSERT_EQ(whole.triangles.size(), expected.size()) << samples << " samples";
    for (std::size_t i = 0; i < expected.size(); ++i) {
      expect_same_setup(whole.triangles[i], expected[i]);
      if (samples > 1) {
        EXPECT_EQ(whole.triangles[i].bounds_fraction, expected[i].bounds_fraction);
      }
    }
    EXPECT_EQ(whole.culled, culled);
    EXPECT_EQ(whole.invalid, invalid);
    EXPECT_EQ(invalid, 1u);
  }
}

}  // namespace
}  // namespace facet::detail
