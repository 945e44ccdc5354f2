// view_command.hpp - `facet view MODEL | --demo NAME`: the interactive viewer (apps/viewer) from the command line.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"

namespace facet::cli {

struct ViewArgs {
  std::string model;
  std::string demo;
  std::string resolution = "1280,720";
  int threads = 0;
  int frames = 0;
  std::string keys;
  std::string screenshot;
  InputArgs input;
  LookArgs look;  // the lighting options only (add_lighting_options)
};

// Adds the `view` subcommand, filling `args` when it is parsed.
CLI::App* add_view_command(CLI::App& app, ViewArgs& args);

// Runs the viewer until its window closes; throws InputError for a model that cannot be loaded, UsageError for bad
// flags, std::runtime_error when no window can be opened (no display) or facet was built without SDL2.
int run_view(const ViewArgs& args);

}  // namespace facet::cli
