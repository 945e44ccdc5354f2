// cpu_level.hpp - which instruction set the pipeline's hot loops run with, and a cap on it (FACET_CPU).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace facet {

// The level the hot loops (detail/dispatch.hpp) run at in this process. On x86-64: "avx512" (x86-64-v4), "avx2"
// (x86-64-v3: AVX2 and FMA), "sse4" (x86-64-v2: SSE4.2) or "baseline" (SSE2), the highest this CPU supports and
// this build compiled, capped by the environment variable FACET_CPU or set_cpu_level. A build without dispatch
// (FACET_NO_DISPATCH) runs "baseline". Elsewhere the build's one target: "neon" on aarch64, "simd128" in the
// browser, "portable" otherwise. `facet bench --json` and `facet render --timings` report it.
// Throws std::invalid_argument if FACET_CPU names no level (see set_cpu_level).
const char* cpu_level();

// The levels this CPU and build can run, lowest first: those cpu_level() may return here.
std::vector<std::string> cpu_levels();

// Caps the level: the hot loops run at no higher level than `name` ("avx512", "avx2", "sse4" or "baseline" on
// x86-64; the build's one level, or "baseline", elsewhere). A level above what the CPU or build offers caps nothing.
// The environment variable FACET_CPU does the same when the process first draws. Every level draws the same
// bytes. Throws std::invalid_argument for any other name. Call it between frames, not while a Renderer draws.
void set_cpu_level(std::string_view name);

namespace detail {
// Throws std::invalid_argument if FACET_CPU is set to a name set_cpu_level would refuse; Renderer's constructor
// calls it, so a bad value stops the first render with that one line.
void check_cpu_level_variable();
}  // namespace detail

}  // namespace facet
