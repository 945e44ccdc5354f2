// render_command.hpp - `facet render MODEL --output out.png`: the flags mapped onto the library's RenderJob.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"

namespace facet::cli {

struct RenderArgs {
  std::vector<std::string> models;
  bool timings = false;  // print each render's stage times on stderr
  std::string views;     // a contact sheet: comma-separated view names
  int turntable = 0;     // a turntable GIF of this many frames
  AnimationSpec animation;
  CameraArgs camera;
  LookArgs look;
  OutputArgs output;
  InputArgs input;
};

// Adds the `render` subcommand, filling `args` when it is parsed.
CLI::App* add_render_command(CLI::App& app, RenderArgs& args);

// One job per model, its output names expanded ({model}, {stem}, {n} counting from first_n; output_template.hpp).
// Throws UsageError for a value CLI11 could not check alone, for several models whose output names hold none of those
// fields, and for two models that would write the same file.
std::vector<RenderJob> render_jobs(const RenderArgs& args, std::size_t first_n = 0);

// Renders every job. With one model, throws InputError for bad input; with several, prints each failure as one
// "facet: error:" line, renders the rest and returns 1 if any failed. Throws UsageError or std::invalid_argument
// for bad usage.
int run_render(const RenderArgs& args);

}  // namespace facet::cli
