// triangle_setup.hpp - what setup hands to rasterization: fixed-point edges, bounds and interpolation planes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "facet/detail/clip.hpp"

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
  Plane depth;       // window z, linear in screen space
  Plane inv_w;       // 1/w
  Plane b1_over_w;   // barycentric weight of source vertex 1, over w
  Plane b2_over_w;   // ... and of source vertex 2; weight 0 is 1 - b1 - b2 after the perspective divide
  std::uint32_t vertex[3];  // source vertices whose varyings are blended, relative to the range the batch shaded
  std::uint32_t primitive;
  bool front_facing;
};

inline float evaluate(const Plane& p, float dx, float dy) { return p.at_origin + p.ddx * dx + p.ddy * dy; }

// Screen coordinate to fixed point. The clamp keeps snapped values within the budget above even when clipping
// rounds a vertex a hair outside the target.
inline std::int32_t snap_to_subpixel(float v, int extent) {
  const float limit = static_cast<float>(extent + 1);
  return static_cast<std::int32_t>(std::lrint(std::clamp(v, -1.0f, limit) * kSubpixelScale));
}

// A vertex after the w-divide, viewport transform and snapping, computed once per vertex in the vertex stage
// (the post-transform cache) so that setup does not repeat it for each of the ~6 triangles sharing the vertex.
// Vertices outside a frustum plane keep only their outcode: their triangles go through the clipper.
struct ProjectedVertex {
  std::int32_t x, y;  // screen, 1/256 pixel, y down
  float z, inv_w;     // window depth and 1/w
  std::uint32_t outcode;
};

// The viewport transform of BENCHMARK.md section 5, in this exact float order (the reference rasterizer repeats it).
inline glm::vec3 screen_from_clip(const glm::vec4& clip, float inv_w, int width, int height) {
  const glm::vec3 ndc = glm::vec3(clip) * inv_w;
  return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(width), (1.0f - ndc.y) * 0.5f * static_cast<float>(height),
          (ndc.z + 1.0f) * 0.5f};
}

// The definition of a projected vertex, one at a time; project_vertices below must agree with it bit for bit.
inline ProjectedVertex project_vertex(const glm::vec4& clip, int width, int height) {
  const std::uint32_t code = outcode(clip);
  if (code) return {0, 0, 0.0f, 0.0f, code};
  const float inv_w = 1.0f / clip.w;
  const glm::vec3 screen = screen_from_clip(clip, inv_w, width, height);
  return {snap_to_subpixel(screen.x, width), snap_to_subpixel(screen.y, height), screen.z, inv_w, 0};
}

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
// dispatch clone; compiled once (src/setup/project.cpp), not per shader.
void project_vertices(const ClipBlock& clip, std::size_t count, ProjectedVertex* out, int width, int height);

}  // namespace facet::detail
