// thumbnail_command.hpp - `facet thumbnail -s SIZE INPUT OUTPUT`: the freedesktop thumbnailer's command line.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "facet/thumbnail.hpp"

namespace facet::cli {

struct ThumbnailArgs {
  std::string input, output;
  int size = kDefaultThumbnailSize;
  double time_limit = kDefaultThumbnailSeconds;
  double max_input_mib = static_cast<double>(kDefaultThumbnailInputBytes >> 20);
  int threads = 0;
};

// Adds the `thumbnail` subcommand, filling `args` when it is parsed.
CLI::App* add_thumbnail_command(CLI::App& app, ThumbnailArgs& args);

// Draws and writes the thumbnail (render_thumbnail) within the time limit: past it, prints one error line and
// exits the process with status 1 before anything is written. The model's warnings are printed once the thumbnail
// is written, so that a failure is one line. Throws as render_thumbnail does.
int run_thumbnail(const ThumbnailArgs& args);

}  // namespace facet::cli
