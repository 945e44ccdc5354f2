// raster_tile.hpp - the per-tile entry point: deferred or immediate shading, compiled per CPU level.
#pragma once

#include <cstddef>
#include <cstdint>

#include "facet/detail/dispatch.hpp"
#include "facet/detail/raster.hpp"
#include "facet/detail/raster_deferred.hpp"
#include "facet/detail/raster_multisample.hpp"

namespace facet::detail {

// Deferred shading needs a shader without discard and colour writes without blending (see raster_deferred.hpp).
template <Shader S>
bool shades_deferred(const RenderState& state) {
  return !ShaderTraits<S>::may_discard && state.defer_shading && state.color_write && state.blend == BlendMode::none;
}
// With colour writes off, a shader without discard changes depth alone: with the depth test and depth writes on,
// its visibility pass is the whole draw.
template <Shader S>
bool writes_depth_only(const RenderState& state) {
  return !ShaderTraits<S>::may_discard && state.defer_shading && !state.color_write && state.depth_test &&
         state.depth_write;
}

// The whole per-tile loop, with coverage, interpolation and the shader inlined into it, is compiled once per CPU
// level (x86-64-v4 with AVX-512, v3 with AVX2 and FMA, and the baseline, which the SSE4.2 level runs too: see
// at_shader_level) and the active level's copy runs (detail/dispatch.hpp), so one binary runs everywhere and the
// 16-lane shading path uses the registers the CPU has, in its lane layout.
template <Shader S>
void raster_tile(const void* draw, const TileWork& work) {
  at_shader_level<ShaderTraits<S>::fragment_lanes_per_level>([&](auto layout) __attribute__((always_inline)) {
    const auto& ctx = *static_cast<const ShadeContext<S>*>(draw);
    if (shades_deferred<S>(*ctx.state)) {
      raster_tile_deferred(ctx, work, layout);
      return;
    }
    if (writes_depth_only<S>(*ctx.state)) {
      raster_tile_depth_only(*ctx.state, work);
      return;
    }
    settle_clear(work, true, true);
    for_each_tile_triangle(work, [&](const TriangleSetup& tri, std::uint32_t) __attribute__((always_inline)) {
      raster_triangle(ctx, tri, work);
    });
  });
}

// raster_tile for a multisampled target (TileWork::samples > 1). A function of its own, not a branch in
// raster_tile: inlined into one body, the two paths made GCC 12 give up vectorising the single-sample visibility
// loops (a frame of sphere:224 took four times as long).
template <Shader S>
void raster_tile_multisample(const void* draw, const TileWork& work) {
  at_shader_level<ShaderTraits<S>::fragment_lanes_per_level>([&](auto layout) __attribute__((always_inline)) {
    const auto& ctx = *static_cast<const ShadeContext<S>*>(draw);
    if (shades_deferred<S>(*ctx.state)) {
      raster_tile_deferred_multisample(ctx, work, layout);
    } else {
      settle_clear(work, true, true);
      for_each_tile_triangle(work, [&](const TriangleSetup& tri, std::uint32_t) __attribute__((always_inline)) {
        raster_triangle_multisample(ctx, tri, work);
      });
    }
  });
}

}  // namespace facet::detail
