// bench_command.hpp - `facet bench`: the end-to-end benchmark defined in docs/BENCHMARK.md.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace facet::cli {

// The flags of docs/BENCHMARK.md section 1, as given; 0 or empty for a scene flag that was not.
struct BenchArgs {
  int sphere = 0, quads = 0;
  std::string mesh, order = "b2f";
  std::string resolution = "1920,1080";
  int frames = 30, warmup = 5;
  int threads = -1;  // not given: every hardware thread
  int samples = 1;   // multisampling: 1, 2, 4 or 8 samples per pixel
  float scale = 1.0f;
  std::string png, depth;
  bool json = false, stats = false;
};

// Adds the `bench` subcommand, filling `args` when it is parsed.
CLI::App* add_bench_command(CLI::App& app, BenchArgs& args);

// Times the frames and prints the result line; returns the exit status. Throws UsageError for a missing scene or
// an unusable mesh (exit status 2), and anything else for other failures (status 1).
int run_bench(const BenchArgs& args);

}  // namespace facet::cli
