// clip.hpp - homogeneous clipping of triangles and lines against the view frustum, positions only.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

namespace facet::detail {

// A clipped vertex remembers where it lies in the source triangle, so that varyings are blended later from the
// source vertices. Clipping therefore never touches varyings and is compiled once for all shaders.
struct ClipVertex {
  glm::vec4 position;  // clip space
  glm::vec3 weights;   // barycentric weights of the source vertices, summing to 1
};

// Six frustum planes -w <= x, y, z <= w, plus w >= kMinW so that nothing at or behind the eye is ever divided by.
inline constexpr int kClipPlanes = 7;
inline constexpr int kMaxClipVertices = 3 + kClipPlanes;  // each plane adds at most one vertex
inline constexpr float kMinW = 1e-5f;

// Signed distance of a clip-space point to plane p (0..5: w + x, w - x, w + y, w - y, w + z, w - z; 6: w - kMinW);
// the point is inside when it is >= 0.
inline float plane_distance(const glm::vec4& v, int plane) {
  switch (plane) {
    case 0: return v.w + v.x;
    case 1: return v.w - v.x;
    case 2: return v.w + v.y;
    case 3: return v.w - v.y;
    case 4: return v.w + v.z;
    case 5: return v.w - v.z;
    default: return v.w - kMinW;
  }
}

// Bit p is set when the point is outside plane p. A point with a NaN or infinite coordinate gets every bit plus
// kNonFinite, and any primitive touching it is dropped whole.
inline constexpr std::uint32_t kNonFinite = 1u << kClipPlanes;

inline std::uint32_t outcode(const glm::vec4& c) {
  if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w)))
    return kNonFinite | (kNonFinite - 1);
  return static_cast<std::uint32_t>(c.w + c.x < 0.0f) | static_cast<std::uint32_t>(c.w - c.x < 0.0f) << 1 |
         static_cast<std::uint32_t>(c.w + c.y < 0.0f) << 2 | static_cast<std::uint32_t>(c.w - c.y < 0.0f) << 3 |
         static_cast<std::uint32_t>(c.w + c.z < 0.0f) << 4 | static_cast<std::uint32_t>(c.w - c.z < 0.0f) << 5 |
         static_cast<std::uint32_t>(c.w - kMinW < 0.0f) << 6;
}

// Clips a triangle; returns the vertex count of the visible convex polygon (0 when nothing is visible), written to
// `out` in the source winding. Triangles with every outcode zero should not be passed here (fast path).
int clip_triangle(const glm::vec4 (&clip)[3], ClipVertex (&out)[kMaxClipVertices]);

// Clips the segment a + t (b - a), t in [0, 1]; returns false if nothing is visible, else the visible [t0, t1].
bool clip_line(const glm::vec4& a, const glm::vec4& b, float& t0, float& t1);

}  // namespace facet::detail
