// reference_rasterizer.hpp - a deliberately simple scalar rasterizer, kept as the test oracle for the fast path.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "core/clip/clip.hpp"
#include "facet/detail/raster.hpp"
#include "facet/framebuffer.hpp"
#include "facet/render_state.hpp"
#include "facet/shader.hpp"

namespace facet::reference {

// Fills the target with a colour and a depth, pixel by pixel: the reference's Renderer::clear plus finish.
inline void clear(Framebuffer& target, glm::vec4 color, float depth = 1.0f) {
  const std::span<std::uint32_t> pixels = target.mutable_color();
  std::fill(pixels.begin(), pixels.end(), pack_rgba8(color));
  const std::span<float> depths = target.mutable_depth();
  std::fill(depths.begin(), depths.end(), depth);
}

// Draws like Renderer::draw, one triangle and one pixel at a time, straight from the definitions: edge functions
// in 64-bit integers at every pixel centre, barycentric weights E_k / area, perspective correction by 1/w. It shares
// only the clipper and the fixed-point snapping convention (8 sub-pixel bits) with the fast path, and writes the
// target's pixels through its public spans (clear it with reference::clear, or with a Renderer and finish()).
// Its top-left rule is its own, written from the definition, as an oracle's should be.
template <Shader S>
void draw(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
          std::span<const std::uint32_t> indices, const RenderState& state = {}) {
  using Varyings = typename S::Varyings;
  constexpr std::size_t kFloats = float_count_v<Varyings>;
  const int width = target.width(), height = target.height();
  const std::span<std::uint32_t> color_buffer = target.mutable_color();
  const std::span<float> depth_buffer = target.mutable_depth();
  const std::size_t count = indices.size() / 3;

  std::vector<VertexOut<Varyings>> shaded;
  shaded.reserve(vertices.size());
  for (const auto& v : vertices) shaded.push_back(shader.vertex(v));

  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  if (state.order == DrawOrder::back_to_front) {
    std::vector<float> key(count, 0.0f);
    for (std::size_t t = 0; t < count; ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = indices[3 * t + k];
        if (i >= shaded.size()) continue;
        const glm::vec4& c = shaded[i].clip;
        key[t] += c.w > detail::kMinW ? c.z / c.w : 1.0f;
      }
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] > key[b]; });
  }

  struct Corner {
    std::int64_t x, y;  // 1/256 pixel, y down
    double z, inv_w;
    glm::dvec3 weights;
  };
  for (const std::uint32_t tri : order) {
    const std::uint32_t source[3] = {indices[3 * tri], indices[3 * tri + 1], indices[3 * tri + 2]};
    if (source[0] >= shaded.size() || source[1] >= shaded.size() || source[2] >= shaded.size()) continue;
    const glm::vec4 clip[3] = {shaded[source[0]].clip, shaded[source[1]].clip, shaded[source[2]].clip};
    detail::ClipVertex polygon[detail::kMaxClipVertices];
    const int n = detail::clip_triangle(clip, polygon);
    if (n < 3) continue;

    std::vector<Corner> corners;
    double polygon_area = 0.0;
    for (int k = 0; k < n; ++k) {
      const glm::vec4& c = polygon[k].position;
      const double inv_w = 1.0 / c.w;
      // Same float arithmetic and snapping as setup, so both rasterizers cover the same pixels.
      const float w_inv = 1.0f / c.w;
      const float sx = (c.x * w_inv + 1.0f) * 0.5f * static_cast<float>(width);
      const float sy = (1.0f - c.y * w_inv) * 0.5f * static_cast<float>(height);
      const float sz = (c.z * w_inv + 1.0f) * 0.5f;
      corners.push_back({std::lrint(std::clamp(sx, -1.0f, width + 1.0f) * 256.0f),
                         std::lrint(std::clamp(sy, -1.0f, height + 1.0f) * 256.0f), sz, inv_w,
                         glm::dvec3(polygon[k].weights)});
    }
    for (int k = 1; k + 1 < n; ++k)
      polygon_area += double(corners[k].x - corners[0].x) * double(corners[k + 1].y - corners[0].y) -
                      double(corners[k + 1].x - corners[0].x) * double(corners[k].y - corners[0].y);
    const bool front = polygon_area < 0.0;  // counter-clockwise with y up
    if (polygon_area == 0.0) continue;
    if ((state.cull == CullMode::back && !front) || (state.cull == CullMode::front && front)) continue;

    for (int f = 1; f + 1 < n; ++f) {
      Corner v[3] = {corners[0], corners[f], corners[f + 1]};
      std::int64_t area = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
      if (area == 0 || (n > 3 && (area < 0) != front)) continue;
      if (area < 0) {
        std::swap(v[1], v[2]);
        area = -area;
      }
      auto edge = [](const Corner& a, const Corner& b, std::int64_t px, std::int64_t py) {
        return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
      };
      auto top_left = [](const Corner& a, const Corner& b) {
        const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
        return (dy == 0 && dx > 0) || dy < 0;
      };
      const std::int64_t min_x = std::min({v[0].x, v[1].x, v[2].x}), max_x = std::max({v[0].x, v[1].x, v[2].x});
      const std::int64_t min_y = std::min({v[0].y, v[1].y, v[2].y}), max_y = std::max({v[0].y, v[1].y, v[2].y});
      const int x0 = std::max<int>(0, static_cast<int>(min_x / 256) - 1);
      const int x1 = std::min<int>(width - 1, static_cast<int>(max_x / 256) + 1);
      const int y0 = std::max<int>(0, static_cast<int>(min_y / 256) - 1);
      const int y1 = std::min<int>(height - 1, static_cast<int>(max_y / 256) + 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const std::int64_t px = 256 * std::int64_t{x} + 128, py = 256 * std::int64_t{y} + 128;
          std::int64_t e[3];
          bool inside = true;
          for (int k = 0; k < 3; ++k) {
            const Corner& a = v[(k + 1) % 3];
            const Corner& b = v[(k + 2) % 3];
            e[k] = edge(a, b, px, py);  // e[k] is opposite corner k, so it weighs corner k
            inside &= e[k] > 0 || (e[k] == 0 && top_left(a, b));
          }
          if (!inside) continue;
          double lambda[3], perspective = 0.0;
          for (int k = 0; k < 3; ++k) {
            lambda[k] = double(e[k]) / double(area);
            perspective += lambda[k] * v[k].inv_w;
          }
          const glm::dvec3 weights = (lambda[0] * v[0].inv_w * v[0].weights + lambda[1] * v[1].inv_w * v[1].weights +
                                      lambda[2] * v[2].inv_w * v[2].weights) /
                                     perspective;
          const float z = std::clamp(
              static_cast<float>(lambda[0] * v[0].z + lambda[1] * v[1].z + lambda[2] * v[2].z) + state.depth_offset,
              0.0f, 1.0f);
          float& stored = depth_buffer[static_cast<std::size_t>(y) * width + x];
          if (state.depth_test && !detail::depth_passes(state.depth_func, z, stored)) continue;

          FloatArray<Varyings> value{};
          for (int k = 0; k < 3; ++k) {
            const FloatArray<Varyings> src = to_floats(shaded[source[k]].varyings);
            for (std::size_t i = 0; i < kFloats; ++i) value[i] += static_cast<float>(weights[k] * src[i]);
          }
          Fragment<Varyings> fragment;
          fragment.varyings = from_floats<Varyings>(value);
          fragment.screen = glm::vec3(x + 0.5f, y + 0.5f, z);
          fragment.primitive = tri;
          fragment.front_facing = front;
          glm::vec4 color;
          if constexpr (ShaderTraits<S>::may_discard) {
            const auto result = shader.fragment(fragment);
            if (!result) continue;
            color = *result;
          } else {
            color = shader.fragment(fragment);
          }
          if (state.depth_test && state.depth_write) stored = z;
          if (!state.color_write) continue;
          std::uint32_t& pixel = color_buffer[static_cast<std::size_t>(y) * width + x];
          if (state.blend == BlendMode::alpha) {
            const float a = std::clamp(color.a, 0.0f, 1.0f);
            const glm::vec4 under = unpack_rgba8(pixel);
            color = glm::vec4(glm::vec3(color) * a + glm::vec3(under) * (1.0f - a), a + under.a * (1.0f - a));
          }
          pixel = pack_rgba8(color);
        }
    }
  }
}

}  // namespace facet::reference
