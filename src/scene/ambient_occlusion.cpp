// ambient_occlusion.cpp - screen-space ambient occlusion from a depth pre-pass: how open each pixel's surface is.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <vector>

#include "facet/detail/dispatch.hpp"
#include "scene/occlusion_kernel.hpp"
#include "scene/scene_impl.hpp"

namespace facet {
namespace detail::occlusion {
namespace {

// Rows go in strips of 16 pixels; the last strip's lanes past the row compute what the padding gives, and are not
// stored where the output has no padding. (Plain loops: a lambda's body would be compiled for the baseline only.)
template <class L>
FACET_LANES_INLINE void store_within(float* out, int x, int width, const simd::FloatT<L>& v) {
  if (x + simd::kLanes <= width) {
    simd::store(out + x, v);
  } else {
    alignas(simd::kLaneAlign) float lanes[simd::kLanes];
    simd::store(lanes, v);
    std::memcpy(out + x, lanes, static_cast<std::size_t>(width - x) * sizeof(float));
  }
}

}  // namespace

// Each CPU level's copy works in its own lane layout L: the whole layout is one 512-bit vector, which copies without
// AVX-512 keep in memory and work on lane by lane.
void depth_row(const Unprojection& unproject, const float* depth, int width, float* z) {
  at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
    using Float = simd::FloatT<L>;
    int x = 0;
    for (; x + simd::kLanes <= width; x += simd::kLanes) {
      const Float d = simd::load<Float>(depth + x);
      // Background strips (window depth 1 throughout) are 0, as Unprojection::z gives them, without its division.
      simd::store(z + x, simd::lane_bits(d < 1.0f) == 0 ? simd::splat<L>(0.0f) : unproject.z(d));
    }
    for (; x < width; ++x) z[x] = unproject.z(depth[x]);
  });
}

void openness_row(const Sampling& sampling, int y, Grid& raw) {
  at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
    using Float = simd::FloatT<L>;
    const float* z = sampling.grid.row(y);
    float* out = raw.row(y);
    for (int x = 0; x < raw.width; x += simd::kLanes) {
      // Most strips of a frame show only the background, or only surface.
      if (simd::lane_bits(simd::load<Float>(z + x) != 0.0f) == 0)
        store_within<L>(out, x, raw.width, simd::splat<L>(1.0f));
      else
        store_within<L>(out, x, raw.width, sampling.openness<Float>(x, y));
    }
  });
}

void blurred_row(const Sampling& sampling, const Grid& raw, int y, float* open) {
  at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
    using Float = simd::FloatT<L>;
    const float* z = sampling.grid.row(y);
    for (int x = 0; x < raw.width; x += simd::kLanes) {
      if (simd::lane_bits(simd::load<Float>(z + x) != 0.0f) == 0)
        store_within<L>(open, x, raw.width, simd::splat<L>(1.0f));
      else
        store_within<L>(open, x, raw.width, sampling.blurred<Float>(raw, x, y));
    }
  });
}

Region region_of(std::span<const ClipBox> boxes, int w, int h) {
  const Region whole{{w, h, 0, 0}, w, h};
  float x_lo = std::numeric_limits<float>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const ClipBox& box : boxes)
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                        (corner & 4) ? box.max.z : box.min.z);
      const glm::vec4 clip = box.clip_from_object * glm::vec4(p, 1.0f);
      if (!(clip.w > 0.0f)) return whole;
      const float x = (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(w);
      const float y = (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(h);
      if (!std::isfinite(x) || !std::isfinite(y)) return whole;
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x), y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    }
  // Pixel centres within [lo, hi], less or more one for rounding, within the target (the values clamped before
  // they become ints: a corner near the eye's plane projects far off).
  const auto pixel = [](float v, int size) {
    return static_cast<int>(std::clamp(v, -2.0f, static_cast<float>(size) + 2.0f));
  };
  const auto first = [&](float lo, int size) { return std::clamp(pixel(std::floor(lo), size) - 1, 0, size); };
  const auto end = [&](float hi, int size) { return std::clamp(pixel(std::ceil(hi), size) + 1, 0, size); };
  if (!(x_lo <= x_hi) || end(x_hi, w) <= first(x_lo, w) || end(y_hi, h) <= first(y_lo, h))
    return {{w, h, 0, 0}, std::min(w, 16), std::min(h, 4)};  // nothing to draw: a strip of background
  const int x0 = first(x_lo, w) / 16 * 16, y0 = first(y_lo, h) / 4 * 4;
  return {{w, h, x0, y0}, end(x_hi, w) - x0, end(y_hi, h) - y0};
}

}  // namespace detail::occlusion

// At half the frame's resolution, from a depth pre-pass: the openness of each pixel's surface within `radius`,
// then a 4 x 4 blur among pixels of similar depth (scene/occlusion_kernel.hpp), over the region the pass can draw.
void Scene::Impl::ambient_occlusion(Renderer& renderer, const SceneOptions& options, const View& view, int width,
                                    int height, float radius) {
  namespace occlusion = detail::occlusion;
  AmbientOcclusion& ao = this->occlusion;
  const int w = (width + 1) / 2, h = (height + 1) / 2;
  if (!ao.target || ao.target->width() != w || ao.target->height() != h)
    ao.target = std::make_unique<Framebuffer>(w, h, 1);
  const glm::mat4 clip_from_world = view.clip_from_view * view.view_from_world;
  renderer.clear(*ao.target, glm::vec4(0.0f), 1.0f);
  draw_depth(renderer, *ao.target, options, clip_from_world, DepthPass::visible);
  renderer.finish(*ao.target);

  // The boxes of the instances the pass draws: those with triangles that meet the frustum.
  std::vector<occlusion::ClipBox> boxes;
  for (const Instance& instance : instances) {
    const detail::PreparedMesh& mesh = prepared.at(instance.mesh.get());
    if (mesh.box.empty() || mesh.groups.empty()) continue;
    const glm::vec4 center = instance.world_from_object * glm::vec4(mesh.center, 1.0f);
    const float radius = mesh.radius * detail::max_scale(instance.world_from_object);
    if (sphere_in_frustum(clip_from_world, glm::vec3(center), radius))
      boxes.push_back({clip_from_world * instance.world_from_object, mesh.box.min, mesh.box.max});
  }
  const occlusion::Region region = occlusion::region_of(boxes, w, h);
  ao.window = region.window;
  // The grids' padding stays zero while their size does; every row is written below.
  if (ao.z.width != region.width || ao.z.height != region.height) {
    ao.z.resize(region.width, region.height);
    ao.raw.resize(region.width, region.height);
  }
  ao.open.resize(static_cast<std::size_t>(region.width) * static_cast<std::size_t>(region.height));
  const std::span<const float> depth = ao.target->depth();
  static const occlusion::Spiral spiral;
  const occlusion::Sampling sampling(ao.z, view.clip_from_view, radius, spiral, region.window);
  const auto rows = [&](auto&& row) {
    renderer.parallel_for(static_cast<std::size_t>(region.height), [&](std::size_t y) { row(static_cast<int>(y)); });
  };
  const auto depth_at = [&](int y) {
    return depth.data() + static_cast<std::size_t>(region.window.y0 + y) * static_cast<std::size_t>(w) +
           static_cast<std::size_t>(region.window.x0);
  };
  const auto open_at = [&](int y) {
    return ao.open.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(region.width);
  };
  rows([&](int y) { occlusion::depth_row(sampling.unproject, depth_at(y), region.width, ao.z.row(y)); });
  rows([&](int y) { occlusion::openness_row(sampling, y, ao.raw); });
  rows([&](int y) { occlusion::blurred_row(sampling, ao.raw, y, open_at(y)); });
}

}  // namespace facet
