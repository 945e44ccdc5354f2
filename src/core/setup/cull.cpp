// cull.cpp - setup's culling tests on 16 triangles at once, branch-free: dense meshes drop most triangles fast.
#include <algorithm>
#include <bit>
#include <cstdint>

#include "facet/detail/dispatch.hpp"
#include "core/setup/setup.hpp"

namespace facet::detail {

// Whether point (cx, cy) lies inside all three clockwise edges from corners X, Y (fill rule included): 1 or 0.
// 32 bits are exact here: bounds of at most four pixels span under 7 pixels (1792 units) each way, so every
// product stays below 2^22. Other lanes may wrap (unsigned, so defined) and are masked by the caller.
[[gnu::always_inline]] inline std::int32_t inside_all(const std::int32_t X[3], const std::int32_t Y[3], std::int32_t cx,
                                                      std::int32_t cy) {
  std::int32_t inside = 1;
  for (int k = 0; k < 3; ++k) {
    const int a = k, b = (k + 1) % 3;
    inside &= edge_function<std::int32_t>(X[b] - X[a], Y[b] - Y[a], X[a], Y[a], cx, cy) >= 0;
  }
  return inside;
}

// Centre of pixel c of bounds 1 to 4 columns wide starting at pixel (px0, py0), pixels in row order, in 1/256 pixel.
[[gnu::always_inline]] inline void bounds_pixel_centre(std::int32_t c, std::int32_t columns, std::int32_t px0,
                                                       std::int32_t py0, std::int32_t& cx, std::int32_t& cy) {
  const std::int32_t row = columns == 1 ? c : (columns == 2 ? c >> 1 : (columns == 3 ? (c == 3) : 0));
  cx = (px0 + c - row * columns) * kSubpixelScale + kSubpixelScale / 2;
  cy = (py0 + row) * kSubpixelScale + kSubpixelScale / 2;
}

// Why a separate pass: in a mesh of millions of triangles most are back faces or too small to hold a pixel centre,
// and which ones is a coin toss per triangle, so a per-triangle branch on it mispredicts about every other
// triangle and throws away the loads already under way for the next ones. Here the tests are plain loops over 16
// triangles that the vectoriser turns into mask operations (64-bit lanes for the exact products), and the only
// branch left is the scalar setup of each survivor. The pass repeats Binner::classify's tests exactly, in the same
// integer arithmetic, for triangles whose corners are all inside the frustum: those it accepts are set up from
// its results without classify; everything else it keeps (a corner outside, an invalid index) goes through the
// full per-triangle path, so it may keep what classify rejects but never rejects what classify keeps.
// kSamples is the sample count, a constant, so that the loop over the sample positions unrolls and each position
// is an immediate.
template <int kSamples>
[[gnu::always_inline]] inline void cull_lanes(const SetupInput& in, std::size_t first, CullLanes& out) {
  constexpr int N = kCullLanes;
  constexpr SamplePattern kPattern = kSamplePatterns[std::countr_zero(static_cast<unsigned>(kSamples))];
  static_assert(kPattern.count == kSamples);
  const std::uint32_t* index = in.indices.data() + 3 * first;
  // An index outside the draw has no projected vertex to read: the scalar path counts such triangles as invalid.
  std::uint32_t highest = 0;
  for (int i = 0; i < 3 * N; ++i) highest = std::max(highest, index[i]);
  if (highest >= in.vertex_count) {
    out.keep = (std::uint32_t{1} << N) - 1;
    out.accepted = 0;
    return;
  }

  std::int32_t x[3][N], y[3][N];
  std::uint32_t outside[N];
  for (int i = 0; i < N; ++i) {
    std::uint32_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const ProjectedVertex& v = in.projected[index[3 * i + k] - in.vertex_first];
      x[k][i] = v.x, y[k][i] = v.y;
      code |= v.outcode;
    }
    outside[i] = code;
  }

  const std::int32_t cull_back = in.cull == CullMode::back, cull_front = in.cull == CullMode::front;
  // Facing first: a mesh's index order keeps neighbours together, so the 16 triangles are often all back faces
  // (half of a closed mesh), and then the costly bounds and centre tests are skipped. That branch follows the
  // mesh's surface, not a coin toss per triangle, so it is mostly predicted. The areas and facing bits are kept
  // for the full pass below.
  std::int64_t area[N];
  std::uint32_t away = 0, clipped = 0;
  for (int i = 0; i < N; ++i) {
    // classify: twice the signed area; counter-clockwise on screen (y down) is negative and front-facing. Culled
    // when zero or facing the culled way.
    area[i] =
        std::int64_t{x[1][i] - x[0][i]} * (y[2][i] - y[0][i]) - std::int64_t{x[2][i] - x[0][i]} * (y[1][i] - y[0][i]);
    const std::int32_t front = area[i] < 0;
    const std::int32_t faced_away = (area[i] == 0) | (cull_back & (front ^ 1)) | (cull_front & front);
    away |= static_cast<std::uint32_t>(faced_away) << i;
    clipped |= static_cast<std::uint32_t>(outside[i] != 0) << i;
  }
  if (away == (std::uint32_t{1} << N) - 1) {
    out.keep = clipped;  // a corner outside the frustum: full setup decides, clipping first
    out.accepted = 0;
    return;
  }

  const std::int32_t last_x = in.width - 1, last_y = in.height - 1;
  const std::int32_t lo = kPattern.lo, hi = kPattern.hi;
  std::uint32_t keep = 0, accepted = 0, small = 0;
  for (int i = 0; i < N; ++i) {
    // Values, not references into the arrays: std::min of references becomes a conditional load, which stops the
    // vectoriser.
    const std::int32_t x0 = x[0][i], x1 = x[1][i], x2 = x[2][i], y0 = y[0][i], y1 = y[1][i], y2 = y[2][i];
    const std::int32_t front = area[i] < 0;
    const std::int32_t faced_away = (away >> i) & 1;
    // Pixels whose centres (multisampled: any of whose samples) lie within the snapped bounds (floor division by
    // 256 is an arithmetic shift).
    const std::int32_t min_x = std::min(std::min(x0, x1), x2), max_x = std::max(std::max(x0, x1), x2);
    const std::int32_t min_y = std::min(std::min(y0, y1), y2), max_y = std::max(std::max(y0, y1), y2);
    const std::int32_t first_x = (min_x - hi + kSubpixelScale - 1) >> kSubpixelBits;
    const std::int32_t first_y = (min_y - hi + kSubpixelScale - 1) >> kSubpixelBits;
    const std::int32_t past_x = (max_x - lo) >> kSubpixelBits, past_y = (max_y - lo) >> kSubpixelBits;
    const std::int32_t px0 = std::max(0, first_x), py0 = std::max(0, first_y);
    const std::int32_t px1 = std::min(last_x, past_x), py1 = std::min(last_y, past_y);
    if constexpr (kSamples > 1)
      out.bounds_fraction[i] =
          bounds_fractions(min_x, min_y, max_x, max_y, first_x, first_y, past_x, past_y, last_x, last_y);
    const std::int32_t empty = (px0 > px1) | (py0 > py1);
    // Bounds holding at most four centres: does any lie inside all three clockwise edges (fill rule included)?
    // Multisampled, the samples are tested after this loop, and only where some bounds are that small.
    const std::int32_t columns = px1 - px0 + 1, centres = columns * (py1 - py0 + 1);
    const std::int32_t few = (empty ^ 1) & (centres <= 4);
    const std::int32_t X[3] = {x0, front ? x2 : x1, front ? x1 : x2};
    const std::int32_t Y[3] = {y0, front ? y2 : y1, front ? y1 : y2};
    std::int32_t covered = kSamples > 1;
    if constexpr (kSamples == 1) {
      for (std::int32_t c = 0; c < 4; ++c) {
        std::int32_t cx, cy;
        bounds_pixel_centre(c, columns, px0, py0, cx, cy);
        covered |= (c < centres) & inside_all(X, Y, cx, cy);
      }
    }
    small |= static_cast<std::uint32_t>(few) << i;
    const std::int32_t rejected = faced_away | empty | (few & (covered ^ 1));
    keep |= static_cast<std::uint32_t>((outside[i] != 0) | (rejected ^ 1)) << i;
    accepted |= static_cast<std::uint32_t>((outside[i] == 0) & (rejected ^ 1)) << i;
    for (int k = 0; k < 3; ++k) out.x[k][i] = X[k], out.y[k][i] = Y[k];
    out.area[i] = front ? -area[i] : area[i];
    out.px0[i] = px0, out.py0[i] = py0, out.px1[i] = px1, out.py1[i] = py1;
    out.front[i] = front;
  }
  if constexpr (kSamples > 1) {
    // Accepted triangles whose bounds hold at most four pixels: does any of their samples lie inside? A second
    // loop, taken only when some bounds are that small, as they are in dense meshes: 4 x kSamples points cost
    // more than the four centres of one sample, and larger triangles cover a sample anyway.
    if (small & accepted) {
      std::uint32_t uncovered = 0;
      for (int i = 0; i < N; ++i) {
        const std::int32_t X[3] = {out.x[0][i], out.x[1][i], out.x[2][i]};
        const std::int32_t Y[3] = {out.y[0][i], out.y[1][i], out.y[2][i]};
        const std::int32_t columns = out.px1[i] - out.px0[i] + 1, pixels = columns * (out.py1[i] - out.py0[i] + 1);
        std::int32_t covered = 0;
        for (std::int32_t c = 0; c < 4; ++c) {
          std::int32_t cx, cy;
          bounds_pixel_centre(c, columns, out.px0[i], out.py0[i], cx, cy);
          for (int n = 0; n < kSamples; ++n)
            covered |= (c < pixels) & inside_all(X, Y, cx + kPattern.offset[n].x, cy + kPattern.offset[n].y);
        }
        uncovered |= static_cast<std::uint32_t>(covered ^ 1) << i;
      }
      uncovered &= small & accepted;
      keep &= ~uncovered;
      accepted &= ~uncovered;
    }
  }
  out.keep = keep;
  out.accepted = accepted;
}

void setup_cull_lanes(const SetupInput& in, std::size_t first, CullLanes& out) {
  at_cpu_level([&]() __attribute__((always_inline)) {
    switch (in.samples) {
      case 2: return cull_lanes<2>(in, first, out);
      case 4: return cull_lanes<4>(in, first, out);
      case 8: return cull_lanes<8>(in, first, out);
      default: return cull_lanes<1>(in, first, out);
    }
  });
}

}  // namespace facet::detail
