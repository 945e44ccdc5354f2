// cpu_level.hpp - which instruction set the pipeline's hot loops run with on this CPU.
#pragma once

namespace facet {

// The level of the hot loops (detail/dispatch.hpp) this process runs: on x86-64 "avx512" (the x86-64-v4 clones),
// "avx2" (x86-64-v3) or "baseline" (SSE2), as the dispatch picks them for this CPU and as the build compiled
// them (a build without dispatch, or a Clang build, runs what its flags name); elsewhere the build's target:
// "neon" on aarch64, "simd128" in the browser, "portable" otherwise. `facet bench --json` and
// `facet render --timings` report it.
const char* cpu_level();

}  // namespace facet
