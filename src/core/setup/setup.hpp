// setup.hpp - primitive assembly, clipping, culling, fixed-point setup and binning of one chunk of primitives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include <glm/glm.hpp>

#include "core/clip/clip.hpp"
#include "facet/detail/binning.hpp"
#include "facet/detail/multisample.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "facet/detail/vertex_stage.hpp"
#include "facet/render_state.hpp"

namespace facet::detail {

struct SetupInput {
  // Post-transform vertices of the range [vertex_first, ...) (see VertexOutputs): vertex i is at i - vertex_first.
  const glm::vec4* clip;             // clip positions, or nullptr: ask clip_position
  const ProjectedVertex* projected;  // projected and snapped (triangles only)
  std::size_t vertex_first;
  ClipPositionFn clip_position;
  const void* clip_source;                 // what clip_position reads
  std::size_t vertex_count;                // of the whole draw: indices at or above it are invalid
  std::span<const std::uint32_t> indices;  // 3 per triangle, 2 per line or 1 per point
  const std::uint32_t* order;              // primitive permutation (painter's algorithm) or nullptr
  std::size_t first, count;                // primitives of this chunk, in draw order
  int width, height, tiles_x;
  CullMode cull;
  float line_width;
  // Samples per pixel (1, 2, 4 or 8), at the positions of sample_pattern: bounds hold the pixels where any sample
  // may be inside, and a triangle whose bounds hold at most four pixels is culled when it covers none of their
  // samples (without multisampling, their centres).
  int samples = 1;
  float point_size = 1.0f;  // pixels: a point's square side or disc diameter
  PointShape point_shape = PointShape::square;
  float point_size_per_w = 0.0f;  // RenderState::point_size_per_w
  bool multisample() const { return samples > 1; }
};

// The vertices that primitives [first, first + count) reference, ignoring indices at or above vertex_count (setup
// skips those primitives).
VertexRange setup_vertex_range(std::span<const std::uint32_t> indices, std::size_t per_primitive,
                               std::size_t vertex_count, std::size_t first, std::size_t count);

void setup_triangles(const SetupInput& input, SetupChunk& out);

// The culling pass's verdict on triangles [first, first + kCullLanes) in index order (no `order`). Bit i of
// `keep` is clear when triangle first + i is one that setup would cull (facing, zero area, no pixel centre
// or sample covered) with all corners inside the frustum, and set when it needs setup; a triangle setup would keep is
// never cleared. Bit i of `accepted` is set when the triangle is valid, inside the frustum and passes every culling
// test: its clockwise corners, area and pixel bounds below are then exactly what setup's own tests would find.
inline constexpr int kCullLanes = 16;
struct CullLanes {
  std::uint32_t keep, accepted;
  std::int32_t x[3][kCullLanes], y[3][kCullLanes];  // snapped corners, clockwise on screen
  std::int64_t area[kCullLanes];                    // twice the area, positive
  std::int32_t px0[kCullLanes], py0[kCullLanes], px1[kCullLanes], py1[kCullLanes];  // pixel bounds
  std::uint32_t bounds_fraction[kCullLanes];  // TriangleSetup::bounds_fraction, multisampled only
  std::int32_t front[kCullLanes];             // 1 when front-facing (then corners 1 and 2 were swapped)
};
void setup_cull_lanes(const SetupInput& input, std::size_t first, CullLanes& out);

// The edge function of clockwise edge (dx, dy) from corner (x_a, y_a) at a point is dx * (y - y_a) - dy * (x - x_a)
// plus this bias, and the point is inside when that is >= 0. Top-left rule, with y down: a top edge is horizontal
// going right, a left edge goes up; a point exactly on any other edge is outside. Bitwise logic, so that it
// vectorises in setup_accepted_lanes and setup_cull_lanes (which computes in 32 bits, hence the template).
template <class I>
[[gnu::always_inline]] inline I top_left_bias(I dx, I dy) {
  return (((dy == 0) & (dx > 0)) | (dy < 0)) ? I{0} : I{-1};
}

// The coverage test, once for every stage that makes it: the edge function of clockwise edge (dx, dy) from corner
// (x_a, y_a) at point (px, py), all in 1/256 pixel, the fill rule's bias included; the point is inside the edge
// when it is >= 0. Culling evaluates it in 32 bits on 16 triangles at once, setup in 64 bits, and the edges that
// raster, visibility and multisampling step across pixels and samples are its linear form (make_edge). Computed
// in I's unsigned type, so that lanes of the cull pass whose products wrap stay defined (their results are
// masked there); exact wherever the products fit in I.
template <class I>
[[gnu::always_inline]] inline I edge_function(I dx, I dy, I x_a, I y_a, I px, I py) {
  using U = std::make_unsigned_t<I>;
  return static_cast<I>(static_cast<U>(dx) * static_cast<U>(py - y_a) - static_cast<U>(dy) * static_cast<U>(px - x_a) +
                        static_cast<U>(top_left_bias(dx, dy)));
}

// The edge function of clockwise edge (dx, dy) from corner (x, y) at the centre of pixel (0, 0): k of Edge.
[[gnu::always_inline]] inline std::int64_t edge_at_centre(std::int64_t dx, std::int64_t dy, std::int64_t x,
                                                          std::int64_t y) {
  return edge_function<std::int64_t>(dx, dy, x, y, kSubpixelScale / 2, kSubpixelScale / 2);
}

// The edge of TriangleSetup from clockwise corner (x, y) along (dx, dy), all in 1/256 pixel (see Edge).
[[gnu::always_inline]] inline Edge make_edge(std::int64_t dx, std::int64_t dy, std::int64_t x, std::int64_t y) {
  // Floor division by the sub-pixel scale: C++20 defines >> on negative values as an arithmetic shift.
  return {static_cast<std::int32_t>(-dy), static_cast<std::int32_t>(dx), edge_at_centre(dx, dy, x, y) >> kSubpixelBits};
}

// The bits of k that make_edge's q drops (TriangleSetup::edge_fraction).
[[gnu::always_inline]] inline std::uint8_t edge_fraction(std::int64_t dx, std::int64_t dy, std::int64_t x,
                                                         std::int64_t y) {
  return static_cast<std::uint8_t>(edge_at_centre(dx, dy, x, y) & (kSubpixelScale - 1));
}

// The plane through (0, 0, f0), (dx1, dy1, f1) and (dx2, dy2, f2), relative to the first corner. Double precision:
// the corner differences and products are exact, so the gradients are correctly rounded once.
[[gnu::always_inline]] inline Plane make_plane(float f0, float f1, float f2, double dx1, double dy1, double dx2,
                                               double dy2, double inv_det) {
  const double d1 = double{f1} - f0, d2 = double{f2} - f0;
  return {f0, static_cast<float>((d1 * dy2 - d2 * dy1) * inv_det), static_cast<float>((d2 * dx1 - d1 * dx2) * inv_det)};
}

// What TriangleSetup holds of each accepted triangle of a culling pass (the same 16 lanes) beyond CullLanes: its
// edges and interpolation planes, bit for bit as the one-at-a-time setup computes them.
struct alignas(64) SetupLanes {
  std::int32_t edge_a[3][kCullLanes], edge_b[3][kCullLanes];
  std::int64_t edge_q[3][kCullLanes];
  std::uint8_t edge_fraction[3][kCullLanes];
  float origin_x[kCullLanes], origin_y[kCullLanes];
  float plane[4][3][kCullLanes];  // depth, 1/w, b1/w, b2/w; each at_origin, ddx, ddy
};
void setup_accepted_lanes(const SetupInput& input, std::size_t first, const CullLanes& cull, SetupLanes& out);

void setup_lines(const SetupInput& input, SetupChunk& out);
// Each point inside the view volume becomes a screen-aligned square or a disc (a polygon) of input.point_size
// pixels (or of input.point_size_per_w / w), as triangles whose corners all carry the point's vertex (see
// Renderer::draw_points).
void setup_points(const SetupInput& input, SetupChunk& out);
// The number of sides of the polygon that stands for a disc of `diameter` pixels: enough that each side stays
// within a tenth of a pixel of the circle, from 8 to kMaxDiscSides.
inline constexpr int kMaxDiscSides = 64;
int disc_sides(float diameter);

// Depth key of every triangle for the painter's algorithm: the mean NDC depth of its corners (larger is farther).
void setup_depth_keys(const glm::vec4* clip, std::size_t vertex_count, std::span<const std::uint32_t> indices,
                      std::span<float> keys);

}  // namespace facet::detail
