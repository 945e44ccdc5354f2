// project.hpp - one vertex from clip space to snapped screen coordinates: the definition project_vertices follows.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "core/clip/clip.hpp"
#include "facet/detail/triangle_setup.hpp"

namespace facet::detail {

// Screen coordinate to fixed point. The clamp keeps snapped values within the budget of Edge (triangle_setup.hpp)
// even when clipping rounds a vertex a hair outside the target.
inline std::int32_t snap_to_subpixel(float v, int extent) {
  const float limit = static_cast<float>(extent + 1);
  return static_cast<std::int32_t>(std::lrint(std::clamp(v, -1.0f, limit) * kSubpixelScale));
}

// The viewport transform of BENCHMARK.md section 5, in this exact float order (the reference rasterizer repeats it).
inline glm::vec3 screen_from_clip(const glm::vec4& clip, float inv_w, int width, int height) {
  const glm::vec3 ndc = glm::vec3(clip) * inv_w;
  return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(width), (1.0f - ndc.y) * 0.5f * static_cast<float>(height),
          (ndc.z + 1.0f) * 0.5f};
}

// The definition of a projected vertex, one at a time; project_vertices (triangle_setup.hpp) must agree with it bit for
// bit.
inline ProjectedVertex project_vertex(const glm::vec4& clip, int width, int height) {
  const std::uint32_t code = outcode(clip);
  if (code) return {0, 0, 0.0f, 0.0f, code};
  const float inv_w = 1.0f / clip.w;
  const glm::vec3 screen = screen_from_clip(clip, inv_w, width, height);
  return {snap_to_subpixel(screen.x, width), snap_to_subpixel(screen.y, height), screen.z, inv_w, 0};
}

}  // namespace facet::detail
