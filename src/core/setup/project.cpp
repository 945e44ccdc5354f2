// project.cpp - outcodes, w-divide, viewport transform and snapping of a block of vertices, vectorised.
#include <cstddef>
#include <cstdint>

#include "core/clip/clip.hpp"
#include "facet/detail/bits.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "core/setup/project.hpp"

namespace facet::detail {
namespace {

std::uint32_t non_finite(float v) { return (detail::bit_cast<std::uint32_t>(v) & 0x7fffffffu) >= 0x7f800000u; }

}  // namespace

// The same operations as project_vertex in the same order, with every branch turned into a select so that the
// loop vectorises (outcode's isfinite as exponent bits, std::clamp as compares, lrint as rint under the same
// rounding mode). A vertex outside any plane gets the same zeros as there.
void project_vertices(const ClipBlock& clip, std::size_t count, ProjectedVertex* __restrict out, int width,
                      int height) {
  at_cpu_level([&]() __attribute__((always_inline)) {
    ProjectedVertex* __restrict projected = out;
    const float w_scale = static_cast<float>(width), h_scale = static_cast<float>(height);
    const float x_limit = static_cast<float>(width + 1), y_limit = static_cast<float>(height + 1);
    const auto snap = [](float v, float limit) {
      const float clamped = v < -1.0f ? -1.0f : (limit < v ? limit : v);
      return static_cast<std::int32_t>(__builtin_rintf(clamped * kSubpixelScale));
    };
    for (std::size_t i = 0; i < count; ++i) {
      const float x = clip.x[i], y = clip.y[i], z = clip.z[i], w = clip.w[i];
      const std::uint32_t outside =
          static_cast<std::uint32_t>(w + x < 0.0f) | static_cast<std::uint32_t>(w - x < 0.0f) << 1 |
          static_cast<std::uint32_t>(w + y < 0.0f) << 2 | static_cast<std::uint32_t>(w - y < 0.0f) << 3 |
          static_cast<std::uint32_t>(w + z < 0.0f) << 4 | static_cast<std::uint32_t>(w - z < 0.0f) << 5 |
          static_cast<std::uint32_t>(w - kMinW < 0.0f) << 6;
      const std::uint32_t bad = non_finite(x) | non_finite(y) | non_finite(z) | non_finite(w);
      const std::uint32_t code = bad ? kNonFinite | (kNonFinite - 1) : outside;
      const float inv_w = 1.0f / w;
      const float screen_x = (x * inv_w + 1.0f) * 0.5f * w_scale;
      const float screen_y = (1.0f - y * inv_w) * 0.5f * h_scale;
      const float screen_z = (z * inv_w + 1.0f) * 0.5f;
      const std::int32_t snapped_x = snap(screen_x, x_limit), snapped_y = snap(screen_y, y_limit);
      const bool inside = code == 0;
      projected[i].x = inside ? snapped_x : 0;
      projected[i].y = inside ? snapped_y : 0;
      projected[i].z = inside ? screen_z : 0.0f;
      projected[i].inv_w = inside ? inv_w : 0.0f;
      projected[i].outcode = code;
    }
  });
}

}  // namespace facet::detail
