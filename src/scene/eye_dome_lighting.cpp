// eye_dome_lighting.cpp - eye-dome lighting: a finished image darkened where the depth steps away from the viewer.
#include "scene/eye_dome_lighting.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "facet/framebuffer.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"

namespace facet::detail {

namespace {

// The neighbours looked at: the eight around the pixel, Potree's eight directions at its default radius of 1.4
// pixels taken to the nearest pixel.
constexpr int kNeighbours[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};

// Boucheny's eye-dome lighting as Potree and Cesium compute it: with L the base-2 logarithm of a pixel's linear
// depth, its response is the mean over its drawn neighbours n of max(0, L - L_n), and its colour is scaled by
// exp(-300 strength response). A pixel with nearer neighbours (a step in depth, the far side of a silhouette
// within the cloud) darkens; a flat region and the background keep their colours, and, as in Cesium, neighbours
// where nothing was drawn count for nothing.
float shade_at(const std::vector<float>& log_depth, int width, int height, int x, int y, float strength) {
  const float own = log_depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  float sum = 0.0f;
  int count = 0;
  for (const auto& offset : kNeighbours) {
    const int nx = x + offset[0], ny = y + offset[1];
    if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
    const float other =
        log_depth[static_cast<std::size_t>(ny) * static_cast<std::size_t>(width) + static_cast<std::size_t>(nx)];
    if (std::isnan(other)) continue;
    sum += std::max(0.0f, own - other);
    ++count;
  }
  return count ? std::exp(-300.0f * strength * (sum / static_cast<float>(count))) : 1.0f;
}

std::uint32_t scaled(std::uint32_t rgba, float shade) {
  std::uint32_t out = rgba & 0xff000000u;  // alpha kept
  for (int c = 0; c < 3; ++c) {
    const float v = static_cast<float>((rgba >> (8 * c)) & 0xffu) * shade;
    out |= static_cast<std::uint32_t>(std::lround(v)) << (8 * c);
  }
  return out;
}

}  // namespace

void apply_eye_dome_lighting(Renderer& renderer, Framebuffer& target, const glm::mat4& clip_from_view, float strength) {
  const int width = target.width(), height = target.height();
  std::vector<float> log_depth = linear_depth(renderer, target, clip_from_view);  // 0 where nothing was drawn
  const auto rows = [&](auto&& row) {
    renderer.parallel_for(static_cast<std::size_t>(height), [&](std::size_t y) { row(static_cast<int>(y)); });
  };
  rows([&](int y) {
    float* row = log_depth.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    for (int x = 0; x < width; ++x)
      row[x] = row[x] > 0.0f ? std::log2(row[x]) : std::numeric_limits<float>::quiet_NaN();
  });
  const std::span<std::uint32_t> color = target.mutable_color();
  rows([&](int y) {
    std::uint32_t* row = color.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    const float* depth = log_depth.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    for (int x = 0; x < width; ++x) {
      if (std::isnan(depth[x])) continue;
      const float shade = shade_at(log_depth, width, height, x, y, strength);
      if (shade < 1.0f) row[x] = scaled(row[x], shade);
    }
  });
}

}  // namespace facet::detail
