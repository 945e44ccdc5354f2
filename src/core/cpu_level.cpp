// cpu_level.cpp - the instruction set level the dispatched hot loops run with, as their resolvers pick it.
#include "facet/cpu_level.hpp"

namespace facet {

const char* cpu_level() {
#if defined(__x86_64__) && !defined(FACET_NO_DISPATCH) && !defined(__clang__)
  // target_clones resolves each function to its best clone this CPU supports, by the same tests.
  __builtin_cpu_init();
#if !defined(FACET_DISPATCH_NO_V4)
  if (__builtin_cpu_supports("x86-64-v4")) return "avx512";
#endif
  if (__builtin_cpu_supports("x86-64-v3")) return "avx2";
  return "baseline";
#elif defined(__x86_64__)
  // One level, the one the build's flags name.
#if defined(__AVX512F__)
  return "avx512";
#elif defined(__AVX2__)
  return "avx2";
#else
  return "baseline";
#endif
#elif defined(__aarch64__)
  return "neon";
#elif defined(__wasm_simd128__)
  return "simd128";
#else
  return "portable";
#endif
}

}  // namespace facet
