// ambient_occlusion.cpp - screen-space ambient occlusion from a depth pre-pass: how open each pixel's surface is.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/scene_impl.hpp"

namespace facet {
namespace {

constexpr int kSamples = 8;  // per pixel, on a spiral; the 4 x 4 pattern of rotations and the blur make it 128
constexpr int kTurns = 3;     // of the spiral, coprime with kSamples so the samples' angles do not repeat
constexpr float kMaxRadiusPixels = 48.0f;  // keeps a close-up's reads near their pixel, in cache
constexpr float kBias = 0.002f;            // of the depth: a flat surface's own samples do not occlude it

// The spiral's offsets for each of the 16 rotations of the 4 x 4 pattern, in units of the screen radius: sample i
// at distance (i + 0.5) / N, angle (i + 0.5) / N turns x kTurns plus the pixel's rotation.
struct Spiral {
  glm::vec2 offset[16][kSamples];
  Spiral() {
    // A 4 x 4 ordered-dither order, so neighbouring pixels take well-separated rotations and the blur averages them.
    constexpr int kOrder[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
    for (int p = 0; p < 16; ++p)
      for (int i = 0; i < kSamples; ++i) {
        const float alpha = (static_cast<float>(i) + 0.5f) / kSamples;
        const float angle = 2.0f * std::numbers::pi_v<float> *
                            (alpha * kTurns + static_cast<float>(kOrder[p]) / 16.0f);
        offset[p][i] = alpha * glm::vec2(std::cos(angle), std::sin(angle));
      }
  }
};

// View-space positions rebuilt from a projection's depth: z from the window depth, x and y from the pixel's
// normalized device coordinates (any projection without shear: perspective, orthographic, off-centre).
struct Unprojection {
  glm::mat4 p;
  int width, height;
  float inverse_x = 1.0f / p[0][0], inverse_y = 1.0f / p[1][1];

  // View-space z of window depth d (negative in front of the eye), or 0 where nothing was drawn (d = 1).
  float z(float d) const {
    if (!(d < 1.0f)) return 0.0f;
    const float ndc = 2.0f * d - 1.0f;
    return (p[3][2] - ndc * p[3][3]) / (ndc * p[2][3] - p[2][2]);
  }
  glm::vec3 position(int x, int y, float z) const {
    const float ndc_x = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
    const float w = p[2][3] * z + p[3][3];
    return {(ndc_x * w - p[2][0] * z - p[3][0]) * inverse_x, (ndc_y * w - p[2][1] * z - p[3][1]) * inverse_y, z};
  }
};

}  // namespace

// Scalable Ambient Obscurance (McGuire, Mara and Luebke, 2012), at half the frame's resolution, from a depth
// pre-pass: each pixel's samples within `radius` of it in the world, seen from its surface's normal (from the
// depth's differences), weigh in by how far above its tangent plane they lie, falling off towards the radius; then
// a 4 x 4 blur among pixels of similar depth removes the rotation pattern's noise.
void Scene::Impl::ambient_occlusion(Renderer& renderer, const SceneOptions& options, const View& view, int width,
                                    int height, float radius) {
  AmbientOcclusion& ao = occlusion;
  const int w = (width + 1) / 2, h = (height + 1) / 2;
  if (!ao.target || ao.target->width() != w || ao.target->height() != h)
    ao.target = std::make_unique<Framebuffer>(w, h, 1);
  renderer.clear(*ao.target, glm::vec4(0.0f), 1.0f);
  draw_depth(renderer, *ao.target, options, view.clip_from_view * view.view_from_world, DepthPass::visible);
  renderer.finish(*ao.target);

  const std::size_t pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  ao.width = w;
  ao.height = h;
  ao.z.resize(pixels);
  ao.raw.resize(pixels);
  ao.open.resize(pixels);
  const std::span<const float> depth = std::as_const(*ao.target).depth();
  const Unprojection unproject{view.clip_from_view, w, h};
  const auto rows = [&](auto&& row) {
    renderer.parallel_for(static_cast<std::size_t>(h), [&](std::size_t y) { row(static_cast<int>(y)); });
  };
  rows([&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      ao.z[i] = unproject.z(depth[i]);
    }
  });

  static const Spiral spiral;
  const glm::mat4& projection = view.clip_from_view;
  // Pixels per world unit at unit clip w: a sphere of the radius spans radius * scale / w pixels.
  const float scale = 0.5f * static_cast<float>(h) * std::abs(projection[1][1]);
  const float r2 = radius * radius;
  const float strength = 5.0f / (kSamples * r2 * r2 * r2);
  const auto z_at = [&](int x, int y) { return ao.z[static_cast<std::size_t>(y) * w + x]; };
  rows([&](int y) {
    for (int x = 0; x < w; ++x) {
      float& out = ao.raw[static_cast<std::size_t>(y) * w + x];
      out = 1.0f;
      const float z = z_at(x, y);
      if (z == 0.0f) continue;
      const glm::vec3 p = unproject.position(x, y, z);
      // The normal from the differences towards the nearer neighbour on each axis (across an edge the other one
      // lies on another surface).
      const auto difference = [&](int dx, int dy) {
        const int xa = x - dx, ya = y - dy, xb = x + dx, yb = y + dy;
        const float za = xa >= 0 && ya >= 0 ? z_at(xa, ya) : 0.0f;
        const float zb = xb < w && yb < h ? z_at(xb, yb) : 0.0f;
        if (za != 0.0f && (zb == 0.0f || std::abs(z - za) < std::abs(zb - z))) return p - unproject.position(xa, ya, za);
        return zb != 0.0f ? unproject.position(xb, yb, zb) - p : glm::vec3(0.0f);
      };
      glm::vec3 n = glm::cross(difference(1, 0), difference(0, 1));
      const float length = glm::length(n);
      if (!(length > 0.0f)) continue;
      n /= length;
      if (glm::dot(n, p) > 0.0f) n = -n;  // towards the eye
      const float screen_radius = std::min(radius * scale / (projection[2][3] * z + projection[3][3]), kMaxRadiusPixels);
      if (screen_radius < 1.0f) continue;
      const glm::vec2* offsets = spiral.offset[(x & 3) + 4 * (y & 3)];
      float sum = 0.0f;
      for (int i = 0; i < kSamples; ++i) {
        const glm::vec2 o = offsets[i] * screen_radius;
        // Rounded to the nearest pixel (the offsets are at most kMaxRadiusPixels: the shift keeps them positive).
        const int sx = x + static_cast<int>(o.x + 64.5f) - 64, sy = y - (static_cast<int>(o.y + 64.5f) - 64);
        if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
        const float sz = z_at(sx, sy);
        if (sz == 0.0f) continue;
        const glm::vec3 v = unproject.position(sx, sy, sz) - p;
        const float vv = glm::dot(v, v), vn = glm::dot(v, n);
        const float falloff = std::max(r2 - vv, 0.0f);
        sum += falloff * falloff * falloff * std::max((vn + kBias * z) / (vv + 0.01f * r2), 0.0f);
      }
      out = std::max(0.0f, 1.0f - sum * strength);
    }
  });
  rows([&](int y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const float z = ao.z[i];
      if (z == 0.0f) {
        ao.open[i] = 1.0f;
        continue;
      }
      float sum = 0.0f, count = 0.0f;
      for (int sy = std::max(y - 1, 0); sy <= std::min(y + 2, h - 1); ++sy)
        for (int sx = std::max(x - 1, 0); sx <= std::min(x + 2, w - 1); ++sx) {
          const std::size_t j = static_cast<std::size_t>(sy) * w + sx;
          if (ao.z[j] == 0.0f || std::abs(ao.z[j] - z) > 0.05f * -z) continue;
          sum += ao.raw[j];
          count += 1.0f;
        }
      ao.open[i] = sum / count;
    }
  });
}

}  // namespace facet
