// raster_deferred.hpp - deferred shading of one tile: a visibility pass over all its triangles, then one shading pass.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "facet/detail/dispatch.hpp"
#include "facet/detail/raster.hpp"
#include "facet/detail/raster_visibility.hpp"
#include "facet/fragment_lanes.hpp"
#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
// GCC 12 reports the strip's FragmentLanes members as maybe-uninitialized where the first triangle writes them;
// prepare_strip_lanes fills every lane of every member before the shader reads it. Clang has no such warning.
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace facet::detail {

// Tile-based deferred shading, as PowerVR-style GPUs do it. When the fragment shader cannot discard and colour is
// written without blending, a pixel's final colour is the colour of the last fragment that passed the depth test
// there, and fragment shaders have no side effects. So the tile first runs coverage and the depth test for all of
// its triangles, in draw order, keeping per pixel the triangle that passed last; then it shades each pixel once,
// with that triangle. The image (colours, depth, derivatives, fill rule) is bit-identical to shading as the
// triangles come, but overdraw costs a depth test instead of a fragment shader.

// Writes colours[k] for the lanes k set in `bits` to the strip's two framebuffer rows.
[[gnu::always_inline]] inline void store_strip(const TileWork& work, int px, int py, unsigned bits,
                                               const std::uint32_t* colors) {
  for (int row = 0; row < 2; ++row) {
    std::uint32_t* out = work.color + work.at(px, py + row);
    const unsigned row_bits = (bits >> (row * 8)) & 0xffu;
    if (row_bits == 0xffu) {
      std::memcpy(out, colors + row * 8, 8 * sizeof(std::uint32_t));
      continue;
    }
    for (unsigned b = row_bits; b; b &= b - 1) {
      const int i = std::countr_zero(b);
      out[i] = colors[row * 8 + i];
    }
  }
}

// The bits of the lanes of a strip whose triangle reference is `ref`: a compare and a mask extraction in the
// layout L's registers. For the whole layout GCC 12 compiles the lane types' compare badly when inlined from the
// baseline: there, a loop, which its vectoriser compiles to one compare and one mask move with AVX-512.
template <class L = simd::Whole>
[[gnu::always_inline]] inline unsigned strip_lanes_equal(const std::uint32_t* refs, std::uint32_t ref) {
#if !defined(__clang__)  // Clang keeps the loop scalar
  if constexpr (L::parts == 1) {
    unsigned bits = 0;
#pragma GCC unroll 1  // kept a loop for the vectoriser: fully unrolled early, it would stay 16 scalar compares
    for (int k = 0; k < simd::kLanes; ++k) bits |= static_cast<unsigned>(refs[k] == ref) << k;
    return bits;
  }
#endif
  return simd::lane_bits(simd::load<simd::UIntT<L>>(refs) == ref);
}

// One lane per triangle of the strip, for the loop over its triangles: the lanes that start a run of one triangle in
// their row, less those in row 1 whose triangle the lane above also has. Every triangle of the strip keeps at least
// one lane (a triangle of row 0 starts a run there). One whose runs in the two rows do not overlap (a slanted edge)
// or whose run in a row is split (by a nearer triangle) keeps more, which costs a repeated interpolation but no
// error; looking further than the lane above makes GCC 12 turn this into scalar code. Unlike picking lanes one
// triangle at a time, the loop over these bits carries no chain of vector compares from one triangle to the next.
// L: the lane layout; each CPU level's copy passes its own, since the whole layout is one 512-bit vector, which
// copies without AVX-512 keep in memory and shuffle lane by lane. With halves or quarters the lane above is the
// part half a strip on, and the lane to the left comes from the part itself and the last lane of the one before.
template <class L>
[[gnu::always_inline]] inline unsigned strip_triangle_starts(const simd::UIntT<L>& refs) {
  using namespace simd;
  using UInt = UIntT<L>;
  UInt left, above;
  if constexpr (L::parts == 1) {
#if defined(__clang__)
    // Clang folds shuffle()'s loop into a shuffle only when it sees literal lane numbers.
    const native::UInt r = refs.part[0];
    left = __builtin_shufflevector(r, r, 15, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14);
    above = __builtin_shufflevector(r, r, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    left = shuffle(refs, (kLaneIndex - 1) & 15), above = shuffle(refs, kLaneIndex ^ 8);
#endif
  } else {
    // Lane j of part i takes lane j - 1 of the part, or for j = 0 the last lane of part i - 1 (of the part itself
    // for the first part: a row's first lane ignores its left).
    const auto index = [](int j) consteval { return j == 0 ? L::width - 1 : L::width + j - 1; };
    constexpr auto lanes = std::make_integer_sequence<int, L::width>{};
    left = UInt::by_part([&](int i) __attribute__((always_inline)) {
      return shuffle_part<decltype(index)>(refs.part[i > 0 ? i - 1 : i], refs.part[i], lanes);
    });
    above = UInt::by_part([&](int i) __attribute__((always_inline)) { return refs.part[(i + L::parts / 2) % L::parts]; });
  }
  const MaskT<L> row_start = (kLaneIndexT<L> & 7) == 0, row_1 = kLaneIndexT<L> >= 8;
  return lane_bits((refs != kNoTriangle) & ((refs != left) | row_start) & ~((refs == above) & row_1));
}

inline const TriangleSetup& triangle_at(const TileWork& work, std::uint32_t ref) {
  return work.chunks[ref >> kTriangleIndexBits].triangles[ref & ((1u << kTriangleIndexBits) - 1)];
}

// The parts (native vectors) of a layout's lanes that hold some of the lanes in `lanes`, a bit per part.
template <class L>
constexpr unsigned parts_with_lanes(unsigned lanes) {
  constexpr unsigned kPartLanes = (1u << L::width) - 1u;
  unsigned parts = 0;
  for (int i = 0; i < L::parts; ++i) parts |= ((lanes >> (i * L::width)) & kPartLanes) != 0 ? 1u << i : 0u;
  return parts;
}

// The lanes of the 2x2 quads that have some of the lanes in `lanes` (lane k is pixel (k % 8, k / 8)).
constexpr unsigned quad_lanes(unsigned lanes) {
  unsigned columns = (lanes | lanes >> 8) & 0xffu;
  columns |= (columns >> 1 & 0x55u) | (columns << 1 & 0xaau);
  return columns | columns << 8;
}

// prepare_strip_lanes' interpolation of one triangle, for layouts of two or four parts: only the parts that hold
// the triangle's lanes (`lanes`), or with derivatives those of its quads, are computed. A small triangle covers
// one or two of a strip's four 128-bit parts (measured on the 200k-triangle OBJ: 1.7 of 4 parts, and 1.5 of 2
// halves), so the lower levels skip half of their interpolation. Each part's lanes get the same operations as with
// the whole layout, so every level's image is the same. The strip's first triangle (kFirst) clears the parts it does
// not compute, so that no lane is left unset; later ones blend their lanes into the parts they compute. `offset`
// is the depth offset, or null where the strip's depth comes from the visibility pass.
template <LaneShader S, class L, bool kFirst>
[[gnu::always_inline]] inline void interpolate_parts(const TriangleSetup& tri, const TileWork& work, std::uint32_t ref,
                                                     unsigned lanes, const float* offset, const simd::UIntT<L>& refs,
                                                     FragmentLanes<typename S::Varyings, L>& fragment) {
  using namespace simd;
  using Float = FloatT<L>;
  using Part = typename Float::Part;
  using IntPart = typename IntT<L>::Part;
  constexpr bool kDerivatives = ShaderTraits<S>::needs_derivatives;
  constexpr std::size_t kFloats = float_count_v<typename S::Varyings>;
  const unsigned parts = parts_with_lanes<L>(kDerivatives ? quad_lanes(lanes) : lanes);
  const auto each_part = [&](auto op) __attribute__((always_inline)) {
#pragma GCC unroll 4
    for (int i = 0; i < L::parts; ++i)
      if (parts >> i & 1u) op(i);
  };
  const auto put = [&]<class Lanes>(Lanes& slot, int i, const typename Lanes::Part& value)
                       __attribute__((always_inline)) {
    if constexpr (kFirst) {
      slot.part[i] = value;
    } else {
      using Bits = IntPart;
      const Bits mine = reinterpret_cast<Bits>(refs.part[i] == ref);
      slot.part[i] = reinterpret_cast<typename Lanes::Part>((reinterpret_cast<Bits>(value) & mine) |
                                                            (reinterpret_cast<Bits>(slot.part[i]) & ~mine));
    }
  };
  if constexpr (kFirst) {
    // Parts without the first triangle: zero until a later triangle blends its lanes in.
    const auto clear = [&](auto& slot) __attribute__((always_inline)) {
      for (int i = 0; i < L::parts; ++i)
        if (!(parts >> i & 1u)) slot.part[i] = typename std::remove_reference_t<decltype(slot)>::Part{};
    };
    if (offset) clear(fragment.depth);
    if constexpr (ShaderTraits<S>::lanes_read_primitive) clear(fragment.primitive), clear(fragment.front_facing);
    for (std::size_t f = 0; f < kFloats; ++f) {
      clear(fragment.varyings[f]);
      if constexpr (kDerivatives) clear(fragment.ddx[f]), clear(fragment.ddy[f]);
    }
  }
  const float* v0 = work.varyings + std::size_t{tri.vertex[0]} * kFloats;
  const float* v1 = work.varyings + std::size_t{tri.vertex[1]} * kFloats;
  const float* v2 = work.varyings + std::size_t{tri.vertex[2]} * kFloats;
  Float b0{}, b1{}, b2{};
  each_part([&](int i) __attribute__((always_inline)) {
    const Part dx = fragment.screen_x.part[i] - tri.origin_x, dy = fragment.screen_y.part[i] - tri.origin_y;
    const auto at = [&](const Plane& p) __attribute__((always_inline)) {
      return p.at_origin + p.ddx * dx + p.ddy * dy;
    };
    if (offset) {
      const Part z = at(tri.depth) + *offset;
      // std::clamp(z, 0, 1), as simd::clamp: NaN stays NaN.
      const IntPart below = z < 0.0f, above = 1.0f < z;
      const IntPart bits = reinterpret_cast<IntPart>(z);
      const IntPart zero = reinterpret_cast<IntPart>(Part{} + 0.0f), one = reinterpret_cast<IntPart>(Part{} + 1.0f);
      put(fragment.depth, i, reinterpret_cast<Part>((below & zero) | (~below & ((above & one) | (~above & bits)))));
    }
    if constexpr (ShaderTraits<S>::lanes_read_primitive) {
      put(fragment.primitive, i, typename UIntT<L>::Part{} + tri.primitive);
      put(fragment.front_facing, i, IntPart{} + (tri.front_facing ? -1 : 0));
    }
    // Perspective-correct weights of the source vertices: b/w and 1/w are linear in screen space.
    const Part w = 1.0f / at(tri.inv_w);
    b1.part[i] = at(tri.b1_over_w) * w, b2.part[i] = at(tri.b2_over_w) * w;
    b0.part[i] = 1.0f - b1.part[i] - b2.part[i];
  });
  for (std::size_t f = 0; f < kFloats; ++f) {
    Float value{};
    each_part([&](int i) __attribute__((always_inline)) {
      value.part[i] = b0.part[i] * v0[f] + b1.part[i] * v1[f] + b2.part[i] * v2[f];
      put(fragment.varyings[f], i, value.part[i]);
    });
    if constexpr (kDerivatives) {
      // Coarse derivatives: within each 2x2 quad, right minus left and bottom minus top of the top-left pixel. The
      // parts computed hold whole quads, so every lane a put reads is the triangle's own.
      const Float origin = quad_top_left(value);
      const Float ddx = quad_top_right(value) - origin, ddy = quad_bottom_left(value) - origin;
      each_part([&](int i) __attribute__((always_inline)) {
        put(fragment.ddx[f], i, ddx.part[i]);
        put(fragment.ddy[f], i, ddy.part[i]);
      });
    }
  }
}

// Shading pass, one strip of a LaneShader: one fragment_lanes call for all 16 pixels, whichever triangles drew
// them. Each triangle of the strip interpolates its varyings at all 16 centres, exactly as shade_quad would (its
// quads' helper pixels included, so derivatives are its own), and its lanes take those values. Dense meshes put
// several triangles in most strips; shading them together costs one interpolation each and one shader call.
// prepare_strip_lanes interpolates (the strip has at least one triangle), finish_strip_lanes shades and stores.
// `depth`, when not null, is the strip's depth as the visibility pass wrote it: each lane's is then already its
// triangle's window depth, computed by the same operations, and is not interpolated again.
template <LaneShader S, class L>
[[gnu::always_inline]] inline void prepare_strip_lanes(const ShadeContext<S>& ctx, const TileWork& work, int px, int py,
                                                       const std::uint32_t* refs, const float* depth,
                                                       FragmentLanes<typename S::Varyings, L>& fragment) {
  using namespace simd;
  using Float = FloatT<L>;
  using UInt = UIntT<L>;
  using Mask = MaskT<L>;
  using Varyings = typename S::Varyings;
  constexpr std::size_t kFloats = float_count_v<Varyings>;
  fragment.screen_x = to_float(kLaneXT<L> + px) + 0.5f;
  fragment.screen_y = to_float(kLaneYT<L> + py) + 0.5f;
  const float offset = ctx.state->depth_offset;
  // kFirst: the strip's first triangle fills every lane, so that none is left unset; later ones blend theirs in.
  // Layouts of several parts interpolate part by part (interpolate_parts); this is the whole layout's way.
  const UInt strip_refs = load<UInt>(refs);
#if defined(__clang__)
  constexpr bool kBlendLanes = true;
#else
  constexpr bool kBlendLanes = false;
#endif
  const auto interpolate = [&]<bool kFirst>(std::uint32_t ref, unsigned lanes) __attribute__((always_inline)) {
    const TriangleSetup& tri = triangle_at(work, ref);
    // The lanes of this triangle take its value. With GCC, a plain loop over the lanes, for the vectoriser (as
    // strip_lanes_equal): the AVX-512 copy compiles it to one compare per triangle and one masked move per slot,
    // folded into the value's last addition (GCC 12 lowers `mask ? a : b` on the lane types lane by lane here).
    // Clang leaves that loop scalar: there, the lane types' bitwise blend.
    const auto put = [&](auto& slot, const auto& value) __attribute__((always_inline)) {
      if constexpr (kFirst) {
        slot = value;
      } else if constexpr (kBlendLanes) {
        slot = simd::blend(strip_refs == ref, value, slot);
      } else {
        // On the lanes' bytes: the vectoriser keeps the lane types' element reads in memory.
        using Lane = typename std::remove_reference_t<decltype(slot)>::scalar_type;
        Lane* lanes = reinterpret_cast<Lane*>(slot.part);
        const Lane* values = reinterpret_cast<const Lane*>(value.part);
#pragma GCC unroll 1
        for (int k = 0; k < kLanes; ++k) lanes[k] = refs[k] == ref ? values[k] : lanes[k];
      }
    };
    if constexpr (L::parts > 1) {
      interpolate_parts<S, L, kFirst>(tri, work, ref, lanes, depth ? nullptr : &offset,
                                      strip_refs, fragment);
    } else {
      const Float dx = fragment.screen_x - tri.origin_x, dy = fragment.screen_y - tri.origin_y;
      const auto at = [&](const Plane& p) __attribute__((always_inline)) {
        return p.at_origin + p.ddx * dx + p.ddy * dy;
      };
      if (!depth) put(fragment.depth, clamp(at(tri.depth) + offset, 0.0f, 1.0f));
      if constexpr (ShaderTraits<S>::lanes_read_primitive) {
        put(fragment.primitive, UInt{} | tri.primitive);
        put(fragment.front_facing, Mask{} | (tri.front_facing ? -1 : 0));
      }
      // Perspective-correct weights of the source vertices: b/w and 1/w are linear in screen space.
      const Float w = 1.0f / at(tri.inv_w);
      const Float b1 = at(tri.b1_over_w) * w, b2 = at(tri.b2_over_w) * w, b0 = 1.0f - b1 - b2;
      const float* v0 = work.varyings + std::size_t{tri.vertex[0]} * kFloats;
      const float* v1 = work.varyings + std::size_t{tri.vertex[1]} * kFloats;
      const float* v2 = work.varyings + std::size_t{tri.vertex[2]} * kFloats;
      for (std::size_t f = 0; f < kFloats; ++f) {
        const Float value = b0 * v0[f] + b1 * v1[f] + b2 * v2[f];
        put(fragment.varyings[f], value);
        if constexpr (ShaderTraits<S>::needs_derivatives) {
          // Coarse derivatives: within each 2x2 quad, right minus left and bottom minus top of the top-left pixel.
          const Float origin = quad_top_left(value);
          put(fragment.ddx[f], quad_top_right(value) - origin);
          put(fragment.ddy[f], quad_bottom_left(value) - origin);
        }
      }
    }
  };
  // Below AVX-512 each triangle is interpolated once: its lanes leave the starts still to visit (a triangle whose
  // runs in the strip do not touch starts more than one; on the 200k-triangle OBJ, one start in seven repeats a
  // triangle). The AVX-512 copy visits every start instead: there, the chain of compares from one triangle to the
  // next cost more than the repeats (a frame of the 200k OBJ 7% slower).
  unsigned pending = strip_triangle_starts<L>(load<simd::UIntT<L>>(refs));
  const auto next = [&]<bool kFirst>() __attribute__((always_inline)) {
    const std::uint32_t ref = refs[std::countr_zero(pending)];
    if constexpr (L::parts > 1) {
      const unsigned lanes = lane_bits(strip_refs == ref);
      pending &= ~lanes;
      interpolate.template operator()<kFirst>(ref, lanes);
    } else {
      pending &= pending - 1;
      interpolate.template operator()<kFirst>(ref, 0u);
    }
  };
  next.template operator()<true>();
  while (pending) next.template operator()<false>();
  if (depth) fragment.depth = load<Float>(depth);
  fragment.active = strip_refs != kNoTriangle;
}

// One fragment_lanes call: the strip's 16 colours, packed, into `colors`. Not inlined: a shader's lane code is most
// of its pipeline's code, and this way it is compiled once per CPU level, not once per path that shades strips
// (single-sampled, with prefetching, multisampled). One call per 16 pixels costs nothing measurable. It takes and
// gives memory, not lane values, whose registers differ between the CPU levels' copies.
template <LaneShader S, class L>
__attribute__((noinline)) void shade_lanes(const S& shader, const FragmentLanes<typename S::Varyings, L>& fragment,
                                           std::uint32_t* colors) {
  at_layout_level<ShaderTraits<S>::fragment_lanes_per_level, L>([&]() __attribute__((always_inline)) {
    simd::store(colors, simd::pack_rgba8(shader.fragment_lanes(fragment)));
  });
}

// The strip's pixels that lie inside the tile (the last tiles of a row or column may be cut short).
inline unsigned strip_inside(const TileWork& work, int px, int py) {
  if (py >= work.y1) return 0u;
  const unsigned row = (1u << std::min(8, work.x1 - px)) - 1u;
  return row | (py + 1 < work.y1 ? row << 8 : 0u);
}

// The lazy clear colour into the strip's lanes set in `bits`.
[[gnu::always_inline]] inline void fill_strip(const TileWork& work, int px, int py, unsigned bits) {
  alignas(64) std::uint32_t colors[simd::kLanes];
  for (int k = 0; k < simd::kLanes; ++k) colors[k] = work.lazy_clear->color_value;
  store_strip(work, px, py, bits, colors);
}

// Shades the prepared strip and stores the colours of its covered lanes, and the lazy clear colour in the `fill`
// lanes, which no triangle covers.
template <LaneShader S, class L>
[[gnu::always_inline]] inline void finish_strip_lanes(const ShadeContext<S>& ctx, const TileWork& work, int px, int py,
                                                      unsigned covered, unsigned fill,
                                                      const FragmentLanes<typename S::Varyings, L>& fragment) {
  using UInt = simd::UIntT<L>;
  alignas(64) std::uint32_t colors[simd::kLanes];
  shade_lanes(*ctx.shader, fragment, colors);
  if (fill)
    simd::store(colors, simd::blend(fragment.active, simd::load<UInt>(colors), UInt{} + work.lazy_clear->color_value));
  store_strip(work, px, py, covered | fill, colors);
}

// A strip prepared ahead of its shading, for shaders that prefetch.
template <Shader S, class L>
struct PreparedStrip {
  FragmentLanes<typename S::Varyings, L> fragment;
  int px, py;
  unsigned covered, fill;
};

// Strips prepared before the first is shaded: prefetch_lanes sees each strip this many strips (a few hundred
// nanoseconds of shading) before fragment_lanes reads what it asked for, about one trip to memory. Measured on
// sphere:224: 2 and 3 alike, 4 1-3% slower, 6 and 8 slower still (more prepared strips to keep in cache).
inline constexpr unsigned kPrefetchDistance = 3;

// Calls copy(scratch, tile, n) for each run of n <= 8 pixels that one row of one block of the tile has: its place
// in the scratch's depth (block by block) and in the tile memory's (row by row). n is the constant 8 in all but a
// cut-short tile's last column, so that the copies of whole rows compile to single vector moves rather than a
// variable-length memcpy.
template <class Copy>
[[gnu::always_inline]] inline void for_each_depth_row(const TileWork& work, Copy&& copy) {
  const int width = work.x1 - work.x0, height = work.y1 - work.y0;
  const int whole = width / kScratchBlock * kScratchBlock;
  for (int y = 0; y < height; ++y) {
    float* scratch_row = work.scratch->depth + (y % kScratchBlock) * kScratchBlock;
    float* tile_row = work.depth + work.at(work.x0, work.y0 + y);
    for (int x = 0; x < whole; x += kScratchBlock)
      copy(scratch_row + scratch_index(x / kScratchBlock, y / kScratchBlock), tile_row + x,
           std::integral_constant<int, kScratchBlock>{});
    if (whole < width)
      copy(scratch_row + scratch_index(whole / kScratchBlock, y / kScratchBlock), tile_row + whole, width - whole);
  }
}

// The tile's depth into its scratch (a pending clear's value, or the tile memory's), and no triangle kept yet.
[[gnu::always_inline]] inline void begin_tile_scratch(const TileWork& work, bool depth_test) {
  if (depth_test)
    for_each_depth_row(
        work, [&](float* scratch, float* tile, auto n) __attribute__((always_inline)) {
          if (work.lazy_clear->depth) std::fill_n(scratch, static_cast<int>(n), work.lazy_clear->depth_value);
          else std::memcpy(scratch, tile, static_cast<std::size_t>(n) * sizeof(float));
        });
  std::fill_n(work.scratch->triangle, kTileSize * kTileSize, kNoTriangle);
}

// The tile's depth back from its scratch.
[[gnu::always_inline]] inline void store_tile_depth(const TileWork& work) {
  for_each_depth_row(
      work, [&](float* scratch, float* tile, auto n) __attribute__((always_inline)) {
        std::memcpy(tile, scratch, static_cast<std::size_t>(n) * sizeof(float));
      });
}

// A tile's draw that writes depth alone (colour writes off, no discard): the visibility pass is the whole draw.
// A depth pre-pass, a shadow map or the occlusion's depth skip the shading pass, and the colour's pending clear
// stays pending, as nothing wrote colour.
[[gnu::always_inline]] inline void raster_tile_depth_only(const RenderState& state, const TileWork& work) {
  begin_tile_scratch(work, true);
  raster_tile_visibility(state, work);
  store_tile_depth(work);
  work.lazy_clear->depth = false;
}

// Asks memory for the varyings of every source vertex of the tile's triangles, before the visibility pass: the
// shading pass reads them in the order its strips come, each a chain of loads (reference, triangle, vertex) that
// would otherwise wait on memory for every vertex the tile has not read yet. Below AVX-512 only: frames of the
// 200k-triangle OBJ and sphere:224 took 3-5% less with AVX2, and the same with AVX-512.
template <Shader S>
[[gnu::always_inline]] inline void prefetch_tile_varyings(const TileWork& work) {
  constexpr std::size_t kBytes = float_count_v<typename S::Varyings> * sizeof(float);
  for_each_tile_triangle(work, [&](const TriangleSetup& tri, std::uint32_t) __attribute__((always_inline)) {
    for (std::uint32_t vertex : tri.vertex) {
      const char* row = reinterpret_cast<const char*>(work.varyings) + vertex * kBytes;
      for (std::size_t line = 0; line < kBytes; line += 64) __builtin_prefetch(row + line);
    }
  });
}

// L: the lane layout of this CPU level's copy (detail/dispatch.hpp).
template <Shader S, class L>
[[gnu::always_inline]] inline void raster_tile_deferred(const ShadeContext<S>& ctx, const TileWork& work, L) {
  const RenderState& state = *ctx.state;
  TileScratch& scratch = *work.scratch;
  const int width = work.x1 - work.x0, height = work.y1 - work.y0;

  begin_tile_scratch(work, state.depth_test);
  if constexpr (ShaderTraits<S>::fragment_lanes && L::parts > 1) prefetch_tile_varyings<S>(work);

  raster_tile_visibility(state, work);

  // With the depth test and depth writes on, the tile's depth holds each pixel's visible triangle's depth.
  const bool depth_resolved = state.depth_test && state.depth_write;
  RenderState resolved = state;
  resolved.depth_test = false;
  const ShadeContext<S> shade{ctx.shader, &resolved};
  using Ahead = std::conditional_t<ShaderTraits<S>::prefetch_lanes, PreparedStrip<S, L>[kPrefetchDistance], char>;
  [[maybe_unused]] Ahead ahead;
  [[maybe_unused]] unsigned prepared = 0;
  for (int block_y = 0; block_y * kScratchBlock < height; ++block_y)
    for (int block_x = 0; block_x * kScratchBlock < width; ++block_x)
      for (int strip = 0; strip < kScratchBlock / 2; ++strip) {
        const std::size_t at = scratch_index(block_x, block_y) + static_cast<std::size_t>(strip) * simd::kLanes;
        const std::uint32_t* refs = scratch.triangle + at;
        const float* depth = depth_resolved ? scratch.depth + at : nullptr;
        const unsigned covered = ~strip_lanes_equal<L>(refs, kNoTriangle) & 0xffffu;
        const int px = work.x0 + block_x * kScratchBlock, py = work.y0 + block_y * kScratchBlock + 2 * strip;
        const unsigned fill = work.lazy_clear->color ? strip_inside(work, px, py) & ~covered : 0u;
        // A lane shader's strip stores the clear colour with its shaded pixels; otherwise it is stored first.
        if (fill && !(ShaderTraits<S>::fragment_lanes && covered)) fill_strip(work, px, py, fill);
        if (!covered) continue;
        if constexpr (ShaderTraits<S>::prefetch_lanes) {
          // Shade the strip prepared kPrefetchDistance strips ago, then prepare this one in its slot.
          PreparedStrip<S, L>& slot = ahead[prepared % kPrefetchDistance];
          if (prepared >= kPrefetchDistance)
            finish_strip_lanes(shade, work, slot.px, slot.py, slot.covered, slot.fill, slot.fragment);
          prepare_strip_lanes(shade, work, px, py, refs, depth, slot.fragment);
          slot.px = px, slot.py = py, slot.covered = covered, slot.fill = fill;
          ctx.shader->prefetch_lanes(slot.fragment);
          ++prepared;
        } else if constexpr (ShaderTraits<S>::fragment_lanes) {
          FragmentLanes<typename S::Varyings, L> fragment;
          prepare_strip_lanes(shade, work, px, py, refs, depth, fragment);
          finish_strip_lanes(shade, work, px, py, covered, fill, fragment);
        } else {
          // One triangle at a time, a quad at a time; ctx's state has the depth test off: it is resolved.
          for (unsigned pending = covered; pending;) {
            const std::uint32_t ref = refs[std::countr_zero(pending)];
            const unsigned same = strip_lanes_equal<L>(refs, ref);
            pending &= ~same;
            shade_block_quads(shade, triangle_at(work, ref), work, px, py, std::uint64_t{same});
          }
        }
      }
  if constexpr (ShaderTraits<S>::prefetch_lanes)
    for (unsigned n = prepared > kPrefetchDistance ? prepared - kPrefetchDistance : 0; n < prepared; ++n) {
      const PreparedStrip<S, L>& slot = ahead[n % kPrefetchDistance];
      finish_strip_lanes(shade, work, slot.px, slot.py, slot.covered, slot.fill, slot.fragment);
    }
  work.lazy_clear->color = false;  // every pixel of the tile is written: shaded or filled

  if (state.depth_test && state.depth_write) {
    store_tile_depth(work);
    work.lazy_clear->depth = false;
  }
}

}  // namespace facet::detail

#pragma GCC diagnostic pop
