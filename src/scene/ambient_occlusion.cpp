// ambient_occlusion.cpp - screen-space ambient occlusion from a depth pre-pass: how open each pixel's surface is.
#include <algorithm>
#include <cstring>

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

}  // namespace detail::occlusion

// At half the frame's resolution, from a depth pre-pass: the openness of each pixel's surface within `radius`,
// then a 4 x 4 blur among pixels of similar depth (scene/occlusion_kernel.hpp).
void Scene::Impl::ambient_occlusion(Renderer& renderer, const SceneOptions& options, const View& view, int width,
                                    int height, float radius) {
  namespace occlusion = detail::occlusion;
  AmbientOcclusion& ao = this->occlusion;
  const int w = (width + 1) / 2, h = (height + 1) / 2;
  if (!ao.target || ao.target->width() != w || ao.target->height() != h)
    ao.target = std::make_unique<Framebuffer>(w, h, 1);
  renderer.clear(*ao.target, glm::vec4(0.0f), 1.0f);
  draw_depth(renderer, *ao.target, options, view.clip_from_view * view.view_from_world, DepthPass::visible);
  renderer.finish(*ao.target);

  if (ao.z.width != w || ao.z.height != h) {
    ao.z.resize(w, h);
    ao.raw.resize(w, h);
  }
  ao.open.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  const std::span<const float> depth = ao.target->depth();
  static const occlusion::Spiral spiral;
  const occlusion::Sampling sampling(ao.z, view.clip_from_view, radius, spiral);
  const auto rows = [&](auto&& row) {
    renderer.parallel_for(static_cast<std::size_t>(h), [&](std::size_t y) { row(static_cast<int>(y)); });
  };
  const auto offset = [w](int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w); };
  rows([&](int y) { occlusion::depth_row(sampling.unproject, depth.data() + offset(y), w, ao.z.row(y)); });
  rows([&](int y) { occlusion::openness_row(sampling, y, ao.raw); });
  rows([&](int y) { occlusion::blurred_row(sampling, ao.raw, y, ao.open.data() + offset(y)); });
}

}  // namespace facet
