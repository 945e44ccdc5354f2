// dispatch.hpp - run-time CPU dispatch: hot loops compiled for several x86-64 levels, one picked per CPU at load.
#pragma once

// FACET_CPU_DISPATCH("arch=x86-64-v3", "default") clones a function for AVX2+FMA CPUs and the baseline; the
// dynamic loader's ifunc resolver picks one, so a single portable binary uses the wide units where they exist.
// Building with FACET_NO_DISPATCH keeps only the baseline: the sanitizer configuration does that, so the
// scalar fallback is tested too.
// Clang 14 cannot clone function templates (the tile loop is one per shader), so a Clang build compiles them once,
// for the target its flags name (-march=native, say).
#if defined(FACET_NO_DISPATCH) || !defined(__x86_64__) || defined(__clang__)
#define FACET_CPU_DISPATCH(...)
#else
#define FACET_CPU_DISPATCH(...) __attribute__((target_clones(__VA_ARGS__)))
#endif

// The levels of the pipeline's hot loops: x86-64-v4 (AVX-512), x86-64-v3 (AVX2, FMA) and the baseline.
// FACET_DISPATCH_NO_V4 leaves out the AVX-512 clone, which costs a third of a shader's compile time: the test
// command builds that way on CPUs without AVX-512, where the clone could never run.
#if defined(FACET_DISPATCH_NO_V4)
#define FACET_DISPATCH_LEVELS FACET_CPU_DISPATCH("arch=x86-64-v3", "default")
#else
#define FACET_DISPATCH_LEVELS FACET_CPU_DISPATCH("arch=x86-64-v4", "arch=x86-64-v3", "default")
#endif
