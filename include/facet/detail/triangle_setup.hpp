// triangle_setup.hpp - what setup hands to rasterization: fixed-point edges, bounds and interpolation planes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace facet::detail {

inline constexpr int kSubpixelBits = 8;  // 1/256 pixel; coordinates up to 16384 px need 22 bits
inline constexpr int kSubpixelScale = 1 << kSubpixelBits;

// A plane value(x, y) = at_origin + ddx * (x - origin_x) + ddy * (y - origin_y) in screen space, where
// (origin_x, origin_y) is the triangle's first vertex; keeping the origin on the triangle avoids cancellation.
struct Plane {
  float at_origin, ddx, ddy;
};

// Coverage of pixel (i, j) by one edge is `a * i + b * j + q >= 0`, exact in integers. The edge function at the
// pixel centre in 1/256-pixel units is 256 * (a * i + b * j) + k, with k holding the +0.5 centre offset and the
// top-left bias; because the first term is a multiple of 256, the test reduces to the above with
// q = floor(k / 256). Inside a partially covered 8x8 block |a * i + b * j + q| stays below 2^26, so the per-pixel
// work fits 32-bit lanes while whole-block decisions use 64 bits.
struct Edge {
  std::int32_t a, b;
  std::int64_t q;
};

struct TriangleSetup {
  Edge edge[3];
  std::int16_t min_x, min_y, max_x, max_y;  // inclusive pixel bounds, clipped to the target
  float origin_x, origin_y;
  Plane depth;              // window z, linear in screen space
  Plane inv_w;              // 1/w
  Plane b1_over_w;          // barycentric weight of source vertex 1, over w
  Plane b2_over_w;          // ... and of source vertex 2; weight 0 is 1 - b1 - b2 after the perspective divide
  std::uint32_t vertex[3];  // source vertices whose varyings are blended, relative to the range the batch shaded
  std::uint32_t primitive;
  bool front_facing;
  // The low 8 bits of each edge's k (see Edge), which q drops: with them the edge can be evaluated exactly at the
  // sample positions of multisampling, which are not pixel centres (see at_sample in multisample.hpp).
  std::uint8_t edge_fraction[3];
  // Multisampled only: the low 8 bits of the snapped corners' extremes, which the pixel bounds drop, min x, min y,
  // max x and max y from bit 0 up (bounds_fractions). With them each sample's own bounds follow from the bounds
  // above (at_sample). 0 for a minimum and 255 for a maximum whose bound was clamped to the target, which leaves
  // that bound as it is.
  std::uint32_t bounds_fraction;
};

// TriangleSetup::bounds_fraction of snapped corner extremes (1/256 pixel) and pixel bounds before and after
// clamping to the target's last pixel (last_x, last_y).
inline std::uint32_t bounds_fractions(std::int32_t min_x, std::int32_t min_y, std::int32_t max_x, std::int32_t max_y,
                                      std::int32_t first_x, std::int32_t first_y, std::int32_t past_x,
                                      std::int32_t past_y, std::int32_t last_x, std::int32_t last_y) {
  constexpr std::int32_t kFraction = kSubpixelScale - 1;
  const std::int32_t low_x = first_x < 0 ? 0 : min_x & kFraction, low_y = first_y < 0 ? 0 : min_y & kFraction;
  const std::int32_t high_x = past_x > last_x ? kFraction : max_x & kFraction;
  const std::int32_t high_y = past_y > last_y ? kFraction : max_y & kFraction;
  return static_cast<std::uint32_t>(low_x | low_y << 8 | high_x << 16 | high_y << 24);
}

inline float evaluate(const Plane& p, float dx, float dy) { return p.at_origin + p.ddx * dx + p.ddy * dy; }

// A vertex after the w-divide, viewport transform and snapping, computed once per vertex in the vertex stage
// (the post-transform cache) so that setup does not repeat it for each of the ~6 triangles sharing the vertex.
// Vertices outside a frustum plane keep only their outcode: their triangles go through the clipper.
struct ProjectedVertex {
  std::int32_t x, y;  // screen, 1/256 pixel, y down
  float z, inv_w;     // window depth and 1/w
  std::uint32_t outcode;
};

// Clip positions of up to kProjectBlock vertices, one array per coordinate: the vertex stage gathers each block's
// positions here, so that project_vertices runs over whole vectors of vertices.
inline constexpr std::size_t kProjectBlock = 64;
struct ClipBlock {
  alignas(64) float x[kProjectBlock];
  alignas(64) float y[kProjectBlock];
  alignas(64) float z[kProjectBlock];
  alignas(64) float w[kProjectBlock];
};

// project_vertex of clip positions [0, count) of the block into out[0, count), branch-free and vectorised in each
// CPU level's copy; compiled once (src/core/setup/project.cpp), not per shader. The one-vertex definition it must agree
// with, project_vertex, is in src/core/setup/project.hpp.
void project_vertices(const ClipBlock& clip, std::size_t count, ProjectedVertex* out, int width, int height);

}  // namespace facet::detail
