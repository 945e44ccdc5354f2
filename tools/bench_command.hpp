// bench_command.hpp - `facet bench`: the end-to-end benchmark defined in docs/BENCHMARK.md.
#pragma once

namespace facet::bench {

// Runs `facet bench` with argv[0] = "bench" and the flags after it; returns the process exit status (0 ok,
// 2 bad arguments or an unloadable mesh, 1 any other failure).
int run_bench(int argc, char** argv);

}  // namespace facet::bench

using facet::bench::run_bench;
