// dispatch.hpp - run-time CPU dispatch: hot loops compiled for several x86-64 levels, one picked per call.
#pragma once

#include <atomic>
#include <type_traits>
#include <utility>

#include "facet/simd.hpp"

namespace facet::detail {

// The x86-64 levels the hot loops are compiled for, lowest first: the baseline (SSE2), x86-64-v2 (SSE4.2),
// x86-64-v3 (AVX2, FMA) and x86-64-v4 (AVX-512).
enum class CpuLevel : int { baseline, sse4, avx2, avx512 };

// The level the hot loops run at: the highest this CPU supports and this build compiled, capped by the environment
// variable FACET_CPU or set_cpu_level (facet/cpu_level.hpp). One relaxed load once known: it is read at every
// dispatched call, some of them per 16 triangles or pixels.
extern std::atomic<int> g_cpu_level;  // a CpuLevel, or -1 until first asked for
int find_cpu_level();                 // src/core/cpu_level.cpp
[[gnu::always_inline]] inline CpuLevel active_cpu_level() {
  const int level = g_cpu_level.load(std::memory_order_relaxed);
  return static_cast<CpuLevel>(level >= 0 ? level : find_cpu_level());
}

}  // namespace facet::detail

// at_cpu_level(body) runs body() compiled for the active level: each level's copy is a function of its own with
// that level's target attribute, into which the body (an always_inline lambda) and everything it inlines are
// compiled. A switch picks the copy at every call, so FACET_CPU and the tests can choose a level at run time (the
// loader's ifunc resolvers of GCC's target_clones choose before any code runs, once and for good), and the same
// source dispatches under GCC and Clang alike, function templates included. Callers dispatch once per tile, chunk,
// row or strip of 16 pixels, so the switch costs nothing measurable.
//
// Building with FACET_NO_DISPATCH keeps only the baseline: the sanitizer configurations do that, so the scalar
// fallback is tested too. FACET_DISPATCH_NO_V4 leaves out the AVX-512 copy, a quarter of a shader's compile time:
// the test command builds that way on CPUs without AVX-512, where it could never run. Off x86-64 (aarch64, the
// browser) there is one level, the one the build targets.
#if defined(__x86_64__) && !defined(FACET_NO_DISPATCH)
#define FACET_DISPATCH_X86 1
#endif

namespace facet::detail {

// The lane layout (simd.hpp) of each level's copy of a shader's stages: one 512-bit vector per lane value with
// AVX-512, two 256-bit ones with AVX2, four 128-bit ones below and off x86-64 (SSE, NEON, WebAssembly SIMD). A
// shader whose lane hooks are not templates on the layout has the whole layout at every level (kPerLevel false).
template <bool kPerLevel>
using Avx512Layout = simd::Whole;
template <bool kPerLevel>
using Avx2Layout = std::conditional_t<kPerLevel, simd::Halves, simd::Whole>;
template <bool kPerLevel>
using BaselineLayout = std::conditional_t<kPerLevel, simd::Quarters, simd::Whole>;

// body(L{}) if the body takes the lane layout, else body().
template <class L, class Body>
[[gnu::always_inline]] inline decltype(auto) call_with_layout(Body& body) {
  if constexpr (std::is_invocable_v<Body&, L>) return body(L{});
  else return body();
}

// body() (or body(layout), with the level's lane layout) compiled for the active level.
template <class Body>
[[gnu::always_inline]] inline decltype(auto) at_cpu_level(Body&& body) {
#if defined(FACET_DISPATCH_X86)
  switch (active_cpu_level()) {
#if !defined(FACET_DISPATCH_NO_V4)
    case CpuLevel::avx512:
      return [&]() __attribute__((target("arch=x86-64-v4"), noinline)) {
        return call_with_layout<Avx512Layout<true>>(body);
      }();
#else
    case CpuLevel::avx512:
#endif
    case CpuLevel::avx2:
      return [&]() __attribute__((target("arch=x86-64-v3"), noinline)) {
        return call_with_layout<Avx2Layout<true>>(body);
      }();
    case CpuLevel::sse4:
      return [&]() __attribute__((target("arch=x86-64-v2"), noinline)) {
        return call_with_layout<BaselineLayout<true>>(body);
      }();
    case CpuLevel::baseline:
      break;
  }
  return [&]() __attribute__((noinline)) { return call_with_layout<BaselineLayout<true>>(body); }();
#else
  return call_with_layout<BaselineLayout<true>>(body);
#endif
}

// at_cpu_level for the stages compiled once per shader (the tile loops, shade_lanes, the vertex stage): body(layout)
// runs with the active level's lane layout. There is no SSE4.2 copy: the SSE4.2 level runs the baseline copy, and its
// own copies of everything else (set-up, visibility, clears). SSE4.2's instructions gained 2-4% a frame over the
// baseline's (docs/PERFORMANCE.md, "Every CPU level"): not worth a fourth copy of every shader's pipeline, a quarter
// of its compile time.
template <bool kPerLevel, class Body>
[[gnu::always_inline]] inline decltype(auto) at_shader_level(Body&& body) {
#if defined(FACET_DISPATCH_X86)
  switch (active_cpu_level()) {
#if !defined(FACET_DISPATCH_NO_V4)
    case CpuLevel::avx512:
      return [&]() __attribute__((target("arch=x86-64-v4"), noinline)) {
        return body(Avx512Layout<kPerLevel>{});
      }();
#else
    case CpuLevel::avx512:
#endif
    case CpuLevel::avx2:
      return [&]() __attribute__((target("arch=x86-64-v3"), noinline)) { return body(Avx2Layout<kPerLevel>{}); }();
    case CpuLevel::sse4:
    case CpuLevel::baseline:
      break;
  }
  return [&]() __attribute__((noinline)) { return body(BaselineLayout<kPerLevel>{}); }();
#else
  return std::forward<Body>(body)(BaselineLayout<kPerLevel>{});
#endif
}

// body() in the copy of the level whose layout L is, for a stage that is handed lane values of layout L by a caller
// already inside that level's copy (shade_lanes). With kPerLevel false every level has the whole layout, and the
// active level picks the copy.
template <bool kPerLevel, class L, class Body>
[[gnu::always_inline]] inline decltype(auto) at_layout_level(Body&& body) {
  if constexpr (!kPerLevel) {
    return at_shader_level<false>([&](L) __attribute__((always_inline)) { return body(); });
  } else {
#if defined(FACET_DISPATCH_X86)
#if !defined(FACET_DISPATCH_NO_V4)
    if constexpr (std::is_same_v<L, Avx512Layout<true>>)
      return [&]() __attribute__((target("arch=x86-64-v4"), noinline)) { return body(); }();
    else
#endif
    if constexpr (std::is_same_v<L, Avx2Layout<true>>)
      return [&]() __attribute__((target("arch=x86-64-v3"), noinline)) { return body(); }();
    else
#endif
    {
      static_assert(std::is_same_v<L, BaselineLayout<true>>);
      return [&]() __attribute__((noinline)) { return body(); }();
    }
  }
}

}  // namespace facet::detail
