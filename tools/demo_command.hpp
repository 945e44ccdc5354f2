// demo_command.hpp - `facet demo cube|torus|two-cubes|pentagon`: built-in demo scenes, one frame or an animation.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"
#include "facet/render_job.hpp"

namespace facet::cli {

struct DemoArgs {
  std::string name;
  LookArgs look;
  OutputArgs output;
  double time = RenderJob{}.time;  // seconds into the animation
  int frames = RenderJob{}.frames;
};

// Adds the `demo` subcommand, filling `args` when it is parsed.
CLI::App* add_demo_command(CLI::App& app, DemoArgs& args);

// Renders the frames; throws UsageError for a frame count without a {frame} pattern, runtime errors for output.
int run_demo(const DemoArgs& args);

}  // namespace facet::cli
