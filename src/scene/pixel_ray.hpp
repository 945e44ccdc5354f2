// pixel_ray.hpp - where a pixel centre's ray meets a triangle: what the normal and motion buffers read at a pixel.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace facet::detail {

// The rays through the pixel centres of a width x height image seen through clip_from_view, in view space: from the
// near plane to the far one, so that oblique and orthographic views work too.
class PixelRays {
 public:
  PixelRays(const glm::mat4& clip_from_view, int width, int height)
      : view_from_clip_(glm::inverse(clip_from_view)), width_(width), height_(height) {}

  struct Ray {
    glm::vec3 origin, direction;
  };
  Ray at(int x, int y) const {
    const float ndc_x = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width_) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_);
    const glm::vec3 origin = point(ndc_x, ndc_y, -1.0f);
    return {origin, point(ndc_x, ndc_y, 1.0f) - origin};
  }

 private:
  glm::vec3 point(float ndc_x, float ndc_y, float ndc_z) const {
    const glm::vec4 p = view_from_clip_ * glm::vec4(ndc_x, ndc_y, ndc_z, 1.0f);
    return glm::vec3(p) / p.w;
  }
  glm::mat4 view_from_clip_;
  int width_, height_;
};

// Where the ray meets the plane of triangle q (view space): barycentric (1 - u - w, u, w) as (u, w), clamped into
// the triangle (Moller-Trumbore, without its range test); the centroid for a ray along the plane.
inline glm::vec2 ray_barycentric(const PixelRays::Ray& ray, const glm::vec3 (&q)[3]) {
  const glm::vec3 e1 = q[1] - q[0], e2 = q[2] - q[0], h = glm::cross(ray.direction, e2);
  const float det = glm::dot(e1, h);
  if (!(std::abs(det) > 0.0f && std::isfinite(det))) return glm::vec2(1.0f / 3.0f);
  const glm::vec3 s = ray.origin - q[0];
  const float u = std::clamp(glm::dot(s, h) / det, 0.0f, 1.0f);
  const float w = std::clamp(glm::dot(ray.direction, glm::cross(s, e1)) / det, 0.0f, 1.0f - u);
  return {u, w};
}

}  // namespace facet::detail
