// render_command.hpp - `facet render MODEL --output out.png`: the flags mapped onto the library's RenderJob.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"

namespace facet::cli {

struct RenderArgs {
  std::string model;
  CameraArgs camera;
  LookArgs look;
  OutputArgs output;
};

// Adds the `render` subcommand, filling `args` when it is parsed.
CLI::App* add_render_command(CLI::App& app, RenderArgs& args);

// The job the flags describe; throws UsageError for a value CLI11 could not check alone.
RenderJob render_job(const RenderArgs& args);

// Runs it; throws InputError for bad input, UsageError or std::invalid_argument for bad usage.
int run_render(const RenderArgs& args);

}  // namespace facet::cli
