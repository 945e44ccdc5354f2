// info_command.hpp - `facet info MODEL`: counts and bounds of a model, one item per line.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"

namespace facet::cli {

struct InfoArgs {
  std::string model;
  InputArgs input;
};

// Adds the `info` subcommand, filling `args` when it is parsed.
CLI::App* add_info_command(CLI::App& app, InfoArgs& args);

// Prints the model's vertex, triangle, edge and material counts and its bounds; throws InputError for bad input.
int run_info(const InfoArgs& args);

}  // namespace facet::cli
