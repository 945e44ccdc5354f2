// thumbnail_command.cpp - `facet thumbnail`: a thumbnail within a hard time limit, for file managers.
#include "thumbnail_command.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "cli_options.hpp"
#include "facet/renderer.hpp"
#include "facet/warnings.hpp"

namespace facet::cli {
namespace {

// Ends the process, with one error line, when the thumbnail is not drawn within the limit. A file manager waits
// on its thumbnailer; a model that takes longer (a huge or hostile file) must not make it wait. Writing is never
// cut short: once the output is being written, the limit no longer applies, so no temporary file is left behind.
class Deadline {
 public:
  Deadline(double seconds, std::string input) : input_(std::move(input)) {
    if (seconds <= 0) return;
    watchdog_ = std::thread([this, seconds] {
      std::unique_lock lock(mutex_);
      const auto limit = std::chrono::duration<double>(seconds);
      if (changed_.wait_for(lock, limit, [this] { return writing_; })) return;
      std::fprintf(stderr, "facet: error: %s: no thumbnail within %g s (--time-limit)\n", input_.c_str(), seconds);
      std::fflush(stderr);
      std::_Exit(1);
    });
  }
  ~Deadline() {
    start_writing();
    if (watchdog_.joinable()) watchdog_.join();
  }
  // From here on the process is not ended.
  void start_writing() {
    const std::lock_guard lock(mutex_);
    writing_ = true;
    changed_.notify_all();
  }

 private:
  std::string input_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool writing_ = false;
  std::thread watchdog_;
};

}  // namespace

CLI::App* add_thumbnail_command(CLI::App& app, ThumbnailArgs& args) {
  CLI::App* thumbnail = app.add_subcommand(
      "thumbnail", "Draw a square thumbnail of a model for a file manager (the freedesktop thumbnailer interface)");
  thumbnail->add_option("input", args.input, "The model: a path or a file:// URI")->required()->type_name("INPUT");
  thumbnail->add_option("output", args.output, "The PNG written (RGBA, with Thumb::URI and Thumb::MTime)")
      ->required()
      ->type_name("OUTPUT.png");
  thumbnail
      ->add_option("-s,--size", args.size,
                   "Width and height in pixels (" + std::to_string(kDefaultThumbnailSize) + ")")
      ->check(number_in(1, kMaxThumbnailSize, true))
      ->type_name("SIZE");
  thumbnail
      ->add_option("--time-limit", args.time_limit,
                   "Give up, exiting with status 1 and writing nothing, after this many seconds; 0: no limit (" +
                       std::to_string(static_cast<int>(kDefaultThumbnailSeconds)) + ")")
      ->check(number_in(0, 86400))
      ->type_name("SECONDS");
  thumbnail
      ->add_option("--max-input-size", args.max_input_mib,
                   "Refuse model files larger than this many MiB (" +
                       std::to_string(kDefaultThumbnailInputBytes >> 20) + ")")
      ->check(number_in(0, 1024))
      ->type_name("MIB");
  thumbnail->add_option("--threads", args.threads, "Render threads; 0 = one per hardware thread (0)")
      ->check(number_in(0, 256, true))
      ->type_name("N");
  return thumbnail;
}

int run_thumbnail(const ThumbnailArgs& args) {
  Deadline deadline(args.time_limit, args.input);
  ThumbnailJob job;
  job.input = args.input;
  job.output = args.output;
  job.size = args.size;
  job.max_input_bytes = static_cast<std::uintmax_t>(args.max_input_mib * 1024.0 * 1024.0);
  job.threads = args.threads;
  Renderer renderer(args.threads);
  // A failed thumbnail says one line, its error: the model's warnings are printed only once it is written.
  WarningCapture warnings;
  const Thumbnail thumbnail = draw_thumbnail(job, renderer);
  deadline.start_writing();
  write_thumbnail(thumbnail, job.output);
  for (const std::string& message : warnings.messages()) std::fprintf(stderr, "facet: warning: %s\n", message.c_str());
  return 0;
}

}  // namespace facet::cli
