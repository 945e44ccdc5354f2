// screen_motion.cpp - where each pixel's surface point goes on the screen between two frames: optical flow's truth.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "facet/scene.hpp"
#include "scene/pixel_ray.hpp"

namespace facet {

namespace {

// A world point's place on a width x height image through a view: pixels from the top-left corner, +y down.
// nullopt behind the eye (a perspective's w not positive).
std::optional<glm::vec2> on_screen(const View& view, glm::vec3 world, int width, int height) {
  const glm::vec4 clip = view.clip_from_view * view.view_from_world * glm::vec4(world, 1.0f);
  if (!(clip.w > 0.0f)) return std::nullopt;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return glm::vec2((ndc.x + 1.0f) * 0.5f * static_cast<float>(width),
                   (1.0f - ndc.y) * 0.5f * static_cast<float>(height));
}

}  // namespace

std::vector<glm::vec2> screen_motion(const Scene& now, const SurfaceIds& ids, const View& view, const Scene& later,
                                     const View& later_view) {
  const std::size_t pixels = static_cast<std::size_t>(ids.width) * static_cast<std::size_t>(ids.height);
  if (ids.instance.size() != pixels || ids.triangle.size() != pixels)
    throw std::invalid_argument("screen_motion: ids do not match their size");
  const std::span<const Instance> from = now.instances(), to = later.instances();
  if (from.size() != to.size())
    throw std::invalid_argument("screen_motion: the later scene has " + std::to_string(to.size()) + " instances, not " +
                                std::to_string(from.size()));
  for (std::size_t i = 0; i < from.size(); ++i)
    if (to[i].mesh->indices != from[i].mesh->indices)
      throw std::invalid_argument("screen_motion: instance " + std::to_string(i) +
                                  "'s mesh has other triangles in the later scene");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<glm::vec2> motion(pixels, glm::vec2(0.0f));
  const detail::PixelRays rays(view.clip_from_view, ids.width, ids.height);
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * ids.width + x;
      const std::uint32_t i = ids.instance[p], t = ids.triangle[p];
      if (i >= from.size() || t >= from[i].mesh->triangle_count()) continue;
      // The point under the pixel centre, as barycentric coordinates of its triangle, carried to the later frame.
      const Mesh& a = *from[i].mesh;
      const Mesh& b = *to[i].mesh;
      glm::vec3 q[3], world_now[3], world_later[3];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = a.indices[3 * t + k];
        world_now[k] = glm::vec3(from[i].world_from_object * glm::vec4(a.positions[v], 1.0f));
        world_later[k] = glm::vec3(to[i].world_from_object * glm::vec4(b.positions[v], 1.0f));
        q[k] = glm::vec3(view.view_from_world * glm::vec4(world_now[k], 1.0f));
      }
      const glm::vec2 u = detail::ray_barycentric(rays.at(x, y), q);
      const auto at = [&](const glm::vec3(&c)[3]) { return (1.0f - u.x - u.y) * c[0] + u.x * c[1] + u.y * c[2]; };
      const std::optional<glm::vec2> start = on_screen(view, at(world_now), ids.width, ids.height);
      const std::optional<glm::vec2> end = on_screen(later_view, at(world_later), ids.width, ids.height);
      motion[p] = start && end ? *end - *start : glm::vec2(nan);
    }
  return motion;
}

}  // namespace facet
