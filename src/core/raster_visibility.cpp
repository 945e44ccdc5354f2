// raster_visibility.cpp - deferred shading's visibility pass: coverage and depth of a tile's triangles, 16 pixels a
// step, compiled once per CPU level for every shader.
#include "facet/detail/raster_visibility.hpp"

#include <cstddef>
#include <cstdint>

#include "facet/detail/bits.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/detail/multisample.hpp"
#include "facet/detail/raster.hpp"
#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet::detail {
namespace {

// The depth tests the visibility pass compiles: LESS and LEQUAL, which depth-tested meshes use, and ALWAYS, which
// the painter's order and drawing without a depth test use (they still write depth), as constants; every other
// function by which of <, ==, > and "unordered" pass (DepthBits), one branch-free form for all of them. The pass is
// compiled five times per CPU level (the four, and once without a test) instead of nine.
enum class DepthTest { less, lequal, always, by_bits };

// Which comparisons of z with the stored depth pass: all bits set (-1) or clear. A NaN on either side is unordered,
// where only NOTEQUAL and ALWAYS pass, as IEEE's comparisons give.
struct DepthBits {
  std::int32_t lt, eq, gt, unordered;
};

inline DepthBits depth_bits(DepthFunc func) {
  switch (func) {
    case DepthFunc::never: return {0, 0, 0, 0};
    case DepthFunc::less: return {-1, 0, 0, 0};
    case DepthFunc::equal: return {0, -1, 0, 0};
    case DepthFunc::lequal: return {-1, -1, 0, 0};
    case DepthFunc::greater: return {0, 0, -1, 0};
    case DepthFunc::notequal: return {-1, 0, -1, -1};
    case DepthFunc::gequal: return {0, -1, -1, 0};
    case DepthFunc::always: return {-1, -1, -1, -1};
  }
  return {0, 0, 0, 0};
}

// Calls body.template operator()<kTest, kDepthTest>() for the state's depth test, so the per-pixel test of the
// visibility pass has no switch inside its loop. Without a depth test nothing is compared.
template <class Body>
[[gnu::always_inline]] inline void with_depth_test(const RenderState& state, Body&& body) {
  if (!state.depth_test) return body.template operator()<DepthTest::always, false>();
  switch (state.depth_func) {
    case DepthFunc::less: return body.template operator()<DepthTest::less, true>();
    case DepthFunc::lequal: return body.template operator()<DepthTest::lequal, true>();
    case DepthFunc::always: return body.template operator()<DepthTest::always, true>();
    default: return body.template operator()<DepthTest::by_bits, true>();
  }
}

template <DepthTest kTest>
[[gnu::always_inline]] inline unsigned depth_test_passes(float z, float stored, const DepthBits& bits) {
  if constexpr (kTest == DepthTest::less) return z < stored;
  else if constexpr (kTest == DepthTest::lequal) return z <= stored;
  else if constexpr (kTest == DepthTest::always) return 1;
  // Bit arithmetic rather than boolean logic: GCC turns the latter into branches, which the vectoriser cannot take.
  return (static_cast<unsigned>(z < stored) & static_cast<unsigned>(bits.lt)) |
         (static_cast<unsigned>(z == stored) & static_cast<unsigned>(bits.eq)) |
         (static_cast<unsigned>(z > stored) & static_cast<unsigned>(bits.gt)) |
         ((static_cast<unsigned>(z != z) | static_cast<unsigned>(stored != stored)) &
          static_cast<unsigned>(bits.unordered));
}

// depth_test_passes for 16 lanes: -1 where the test passes, 0 where it fails.
template <DepthTest kTest, class L>
[[gnu::always_inline]] inline simd::MaskT<L> depth_test_passes(const simd::FloatT<L>& z, const simd::FloatT<L>& stored,
                                                             const DepthBits& bits) {
  if constexpr (kTest == DepthTest::less) return z < stored;
  else if constexpr (kTest == DepthTest::lequal) return z <= stored;
  else if constexpr (kTest == DepthTest::always) return simd::splat<L>(-1);
  return ((z < stored) & bits.lt) | ((z == stored) & bits.eq) | ((z > stored) & bits.gt) |
         (((z != z) | (stored != stored)) & bits.unordered);
}

// An edge value the strip loop treats as "inside everywhere": far above any offset within a block (|a|, |b| < 2^22,
// so offsets stay within 2^26) and far below overflow.
inline constexpr std::int32_t kEdgeInside = 1 << 30;


// Whether the primitive is a screen-aligned rectangle (setup's `rectangle`, a point's square: edges that pass
// everywhere, which no triangle has, and a flat depth) of at most kSmallRectangle pixels each way. Such a point's
// pixels are few: a loop over them costs less than the strips' 16 lanes and their edge set-up.
inline constexpr int kSmallRectangle = 8;
inline bool is_small_rectangle(const TriangleSetup& tri) {
  const Edge* e = tri.edge;
  const bool passes_everywhere =
      (e[0].a | e[0].b | e[1].a | e[1].b | e[2].a | e[2].b) == 0 && (e[0].q | e[1].q | e[2].q) >= 0;
  return passes_everywhere && tri.depth.ddx == 0.0f && tri.depth.ddy == 0.0f &&
         tri.max_x - tri.min_x < kSmallRectangle && tri.max_y - tri.min_y < kSmallRectangle;
}

// Visibility of one triangle in one tile. Per 8x8 block: hierarchical depth rejects hidden blocks, and then each 8x2
// strip of the block's rectangle runs one branch-free loop over its 16 pixels that does the three edge tests, the
// depth test and the stores together. Edge values come in 32 bits straight from the triangle's corner for all but
// huge triangles (kSmallTriangleSpan); a huge one's are classified per block in 64 bits first (exact: outside,
// inside, or crossing), and an edge that has the whole block inside becomes the constant kEdgeInside.
// With 256- and 512-bit vectors it is written as plain loops, not with the lane types: the loop vectoriser runs
// after inlining, inside each dispatch copy, and emits that copy's mask instructions, where GCC 12 lowers some
// lane-type idioms (broadcasts, -1/0 masks) element by element. With 128-bit vectors GCC 12 leaves those loops
// scalar (the SSE4.2 copy's pass took 5 times the AVX-512 one's time), and Clang does at every level: there the
// lane types of the level's layout L do the same tests and arithmetic, in the same order. The coverage is exactly
// raster_block_coverage's (see Edge for the 32-bit budget).
template <DepthTest kTest, bool kDepthTest, class L>
[[gnu::always_inline]] inline void raster_triangle_visibility(const TriangleSetup& tri, const RenderState& state,
                                                              const TileWork& work, std::uint32_t ref) {
#if defined(__clang__)
  constexpr bool kLanePath = true;
#else
  constexpr bool kLanePath = L::parts == 4;
#endif
  const bool depth_write = kDepthTest && state.depth_write;
  const float offset = state.depth_offset;
  [[maybe_unused]] const DepthBits passing =
      kDepthTest && kTest == DepthTest::by_bits ? depth_bits(state.depth_func) : DepthBits{};
  const float origin_x = tri.origin_x, origin_y = tri.origin_y;
  const Plane plane = tri.depth;

  // The strips of rows [j0, j1] of the block at (bx, by) within `rect`, with edge values base + step_x * i +
  // step_y * j at its pixel (i, j). Returns whether any pixel passed.
  const auto strips = [&](int bx, int by, int j0, int j1, std::uint64_t rect, const std::int32_t* base,
                          const std::int32_t* step_x, const std::int32_t* step_y) __attribute__((always_inline)) {
    const std::int32_t a0 = step_x[0], b0 = step_y[0], a1 = step_x[1], b1 = step_y[1], a2 = step_x[2], b2 = step_y[2];
    const std::size_t block = scratch_index((bx - work.x0) / kScratchBlock, (by - work.y0) / kScratchBlock);
    if constexpr (kLanePath) {
      using namespace simd;
      FACET_LANE_TYPES(L);
      // Per block: each lane's offset from the strip's edge values, and the depth plane along x. The same integer
      // sums and the same float operations in the same order as the scalar path, so the same bits.
      const Int lane_x = kLaneXT<L>, lane_y = kLaneYT<L>;
      const Int o0 = a0 * lane_x + b0 * lane_y, o1 = a1 * lane_x + b1 * lane_y, o2 = a2 * lane_x + b2 * lane_y;
      const Int lane_bit = Int{} + 1 << kLaneIndexT<L>;
      [[maybe_unused]] Float z_x;
      if constexpr (kDepthTest) z_x = plane.at_origin + plane.ddx * (to_float(lane_x + bx) + 0.5f - origin_x);
      Mask passed{};
      for (int strip = j0 / 2; strip <= j1 / 2; ++strip) {
        const std::int32_t bits = static_cast<std::int32_t>((rect >> (strip * kLanes)) & 0xffffu);
        float* depth = work.scratch->depth + block + static_cast<std::size_t>(strip) * kLanes;
        std::uint32_t* triangle = work.scratch->triangle + block + static_cast<std::size_t>(strip) * kLanes;
        const std::int32_t e0 = base[0] + 2 * strip * b0, e1 = base[1] + 2 * strip * b1, e2 = base[2] + 2 * strip * b2;
        Mask pass = (lane_bit & bits) != 0;
        pass &= ((e0 + o0) | (e1 + o1) | (e2 + o2)) >= 0;
        Float z{};
        const Float stored = load<Float>(depth);
        if constexpr (kDepthTest) {
          const Float dy = to_float(lane_y + (by + 2 * strip)) + 0.5f - origin_y;
          z = z_x + plane.ddy * dy + offset;
          z = select(z < 0.0f, splat<L>(0.0f), select(1.0f < z, splat<L>(1.0f), z));  // as the scalar clamp
          pass &= depth_test_passes<kTest>(z, stored, passing);
        }
        if (depth_write) {
          passed |= pass;
          store(depth, blend(pass, z, stored));
        }
        store(triangle, blend(pass, UInt{} + ref, load<UInt>(triangle)));
      }
      return lane_bits(passed);
    } else {
      unsigned any = 0;
      for (int strip = j0 / 2; strip <= j1 / 2; ++strip) {
        const unsigned bits = static_cast<unsigned>(rect >> (strip * simd::kLanes)) & 0xffffu;
        float* depth = work.scratch->depth + block + static_cast<std::size_t>(strip) * simd::kLanes;
        std::uint32_t* triangle = work.scratch->triangle + block + static_cast<std::size_t>(strip) * simd::kLanes;
        const int py = by + 2 * strip;
        // Only locals inside the loops: the triangle's fields, read there, might alias the stores through depth[]
        // and triangle[] as far as GCC knows, and that keeps it from vectorising.
        const std::int32_t e0 = base[0] + 2 * strip * b0, e1 = base[1] + 2 * strip * b1,
                           e2 = base[2] + 2 * strip * b2;
        // Branch-free, so that the loops vectorise: bitwise &, selects, and stores of the old value where nothing
        // passes.
        const auto lane_pass = [&](int k, float& z) __attribute__((always_inline)) {
          // Inside all three edges when no value has its sign bit set. Bit arithmetic rather than compares: GCC
          // turns a chain of boolean &s into branches, which the vectoriser cannot take.
          const int i = k & 7, j = k >> 3;
          const std::int32_t signs = (e0 + a0 * i + b0 * j) | (e1 + a1 * i + b1 * j) | (e2 + a2 * i + b2 * j);
          unsigned pass = (bits >> k) & (~static_cast<std::uint32_t>(signs) >> 31);
          if constexpr (kDepthTest) {
            const float dx = static_cast<float>(bx + (k & 7)) + 0.5f - origin_x;
            const float dy = static_cast<float>(py + (k >> 3)) + 0.5f - origin_y;
            z = evaluate(plane, dx, dy) + offset;
            z = z < 0.0f ? 0.0f : (1.0f < z ? 1.0f : z);  // std::clamp(z, 0, 1), NaN kept, as shade_quad
            pass &= depth_test_passes<kTest>(z, depth[k], passing);
          }
          return pass;
        };
        if (depth_write) {
          for (int k = 0; k < simd::kLanes; ++k) {
            float z = 0.0f;
            const unsigned pass = lane_pass(k, z);
            any |= pass;
            depth[k] = pass ? z : depth[k];
            triangle[k] = pass ? ref : triangle[k];
          }
        } else {
          for (int k = 0; k < simd::kLanes; ++k) {
            float z = 0.0f;
            triangle[k] = lane_pass(k, z) ? ref : triangle[k];
          }
        }
      }
      return any;
    }
  };

  if (is_small_rectangle(tri)) {
    // One depth everywhere (the plane is flat: 0 times any pixel's offset), as the strips would compute it.
    float z = 0.0f;
    if constexpr (kDepthTest) {
      z = evaluate(plane, static_cast<float>(tri.min_x) + 0.5f - origin_x,
                   static_cast<float>(tri.min_y) + 0.5f - origin_y) + offset;
      z = z < 0.0f ? 0.0f : (1.0f < z ? 1.0f : z);
    }
    raster_blocks(
        tri, work, kDepthTest, state,
        [&](int bx, int by, int i0, int i1, int j0, int j1) __attribute__((always_inline)) {
          const std::size_t block = scratch_index((bx - work.x0) / kScratchBlock, (by - work.y0) / kScratchBlock);
          unsigned any = 0;
          for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
              // The scratch holds a block's pixels row by row (two rows a strip).
              const std::size_t at = block + static_cast<std::size_t>(j * kScratchBlock + i);
              float& depth = work.scratch->depth[at];
              std::uint32_t& triangle = work.scratch->triangle[at];
              unsigned pass = 1;
              if constexpr (kDepthTest) pass = depth_test_passes<kTest>(z, depth, passing);
              // Selects by mask, not branches: whether a point's pixel passes is a coin toss in a dense cloud.
              const std::uint32_t keep = pass - 1u;  // all ones where it fails
              if (depth_write) {
                any |= pass;
                depth = bit_cast<float>((bit_cast<std::uint32_t>(z) & ~keep) | (bit_cast<std::uint32_t>(depth) & keep));
              }
              triangle = (ref & ~keep) | (triangle & keep);
            }
          return BlockCoverage{any != 0, i0 == 0 && j0 == 0 && i1 == kBlockSize - 1 && j1 == kBlockSize - 1};
        });
    return;
  }

  if (tri.max_x - tri.min_x <= kSmallTriangleSpan && tri.max_y - tri.min_y <= kSmallTriangleSpan) {
    std::int32_t at_min[3], step_x[3], step_y[3];
    for (int e = 0; e < 3; ++e) {
      const Edge& edge = tri.edge[e];
      at_min[e] =
          static_cast<std::int32_t>(std::int64_t{edge.a} * tri.min_x + std::int64_t{edge.b} * tri.min_y + edge.q);
      step_x[e] = edge.a;
      step_y[e] = edge.b;
    }
    raster_blocks(
        tri, work, kDepthTest,
        state, [&](int bx, int by, int i0, int i1, int j0, int j1) __attribute__((always_inline)) {
          std::int32_t base[3];
          for (int e = 0; e < 3; ++e) base[e] = at_min[e] + step_x[e] * (bx - tri.min_x) + step_y[e] * (by - tri.min_y);
          const std::uint64_t rect = block_rect_mask(i0, i1, j0, j1);
          // Whether every pixel of the block is inside: only then can the block's depth bound tighten.
          bool full = rect == ~std::uint64_t{0};
          if (full)
            for (int e = 0; e < 3; ++e)
              full &=
                  base[e] + std::min(0, step_x[e] * (kBlockSize - 1)) + std::min(0, step_y[e] * (kBlockSize - 1)) >= 0;
          return BlockCoverage{strips(bx, by, j0, j1, rect, base, step_x, step_y) != 0, full};
        });
    return;
  }

  raster_blocks(
      tri, work, kDepthTest, state, [&](int bx, int by, int i0, int i1, int j0, int j1) __attribute__((always_inline)) {
        // Each edge on the block's rectangle [i0, i1] x [j0, j1]: its extremes are at corners (exact in 64 bits). An
        // edge the whole rectangle is inside of becomes the constant kEdgeInside (steps 0), with selects rather than
        // branches: which edges those are is a coin toss per block.
        std::int32_t base[3], step_x[3], step_y[3];
        bool outside = false, all_inside = true;
        for (int e = 0; e < 3; ++e) {
          const Edge& edge = tri.edge[e];
          const std::int64_t at_block = std::int64_t{edge.a} * bx + std::int64_t{edge.b} * by + edge.q;
          const std::int64_t at_corner = at_block + std::int64_t{edge.a} * i0 + std::int64_t{edge.b} * j0;
          const std::int64_t step_a = std::int64_t{edge.a} * (i1 - i0), step_b = std::int64_t{edge.b} * (j1 - j0);
          const std::int64_t lowest = at_corner + std::min<std::int64_t>(0, step_a) + std::min<std::int64_t>(0, step_b);
          const std::int64_t highest =
              at_corner + std::max<std::int64_t>(0, step_a) + std::max<std::int64_t>(0, step_b);
          outside |= highest < 0;
          all_inside &= lowest >= 0;
          const bool inside = lowest >= 0;
          base[e] = inside ? kEdgeInside : static_cast<std::int32_t>(at_block);
          step_x[e] = inside ? 0 : edge.a;
          step_y[e] = inside ? 0 : edge.b;
        }
        if (outside) return BlockCoverage{false, false};
        const std::uint64_t rect = block_rect_mask(i0, i1, j0, j1);
        const bool any = strips(bx, by, j0, j1, rect, base, step_x, step_y) != 0;
        return BlockCoverage{any, all_inside && rect == ~std::uint64_t{0}};
      });
}

}  // namespace

// Both passes take the depth function as a constant (with_depth_func), so the per-pixel test has no switch inside
// the loops; the helpers above are inlined into each CPU level's clone. Without a depth test the function is
// `always`, so only that one is compiled without the test.
void raster_tile_visibility(const RenderState& state, const TileWork& work) {
  at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
    with_depth_test(state, [&]<DepthTest kTest, bool kDepthTest>() __attribute__((always_inline)) {
      for_each_tile_triangle(work, [&](const TriangleSetup& tri, std::uint32_t ref) __attribute__((always_inline)) {
        raster_triangle_visibility<kTest, kDepthTest, L>(tri, state, work, ref);
      });
    });
  });
}

void raster_tile_visibility_multisample(const RenderState& state, const TileWork& work, const TileWork* planes) {
  at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
    const int n = work.samples;
    const SamplePattern& pattern = sample_pattern(n);
    with_depth_test(state, [&]<DepthTest kTest, bool kDepthTest>() __attribute__((always_inline)) {
      for_each_tile_triangle(work, [&](const TriangleSetup& tri, std::uint32_t ref) __attribute__((always_inline)) {
        for (int s = 0; s < n; ++s)
          raster_triangle_visibility<kTest, kDepthTest, L>(at_sample(tri, pattern, s), state, planes[s], ref);
      });
    });
  });
}

}  // namespace facet::detail

#pragma GCC diagnostic pop
