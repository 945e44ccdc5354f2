// clip.hpp - homogeneous clipping of triangles and lines against the view frustum, positions only.
#pragma once

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

// Bit p is set when the point is outside plane p. NaN coordinates are reported outside every plane.
std::uint32_t outcode(const glm::vec4& clip);

// Clips a triangle; returns the vertex count of the visible convex polygon (0 when nothing is visible), written to
// `out` in the source winding. Triangles with every outcode zero should not be passed here (fast path).
int clip_triangle(const glm::vec4 (&clip)[3], ClipVertex (&out)[kMaxClipVertices]);

// Clips the segment a + t (b - a), t in [0, 1]; returns false if nothing is visible, else the visible [t0, t1].
bool clip_line(const glm::vec4& a, const glm::vec4& b, float& t0, float& t1);

}  // namespace facet::detail
