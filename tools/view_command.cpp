// view_command.cpp - `facet view`: parses the viewer's flags and hands them to apps/viewer.
#include "view_command.hpp"

#include <stdexcept>

#include "cli_options.hpp"
#include "facet/demo_scenes.hpp"
#include "facet/image_io.hpp"
#include "facet/render_job.hpp"
#if FACET_HAVE_VIEWER
#include "viewer/keys.hpp"
#include "viewer/viewer.hpp"
#endif

namespace facet::cli {

CLI::App* add_view_command(CLI::App& app, ViewArgs& args) {
#if FACET_HAVE_VIEWER
  const std::string keys = std::string("\nKeys:\n") + viewer::kHelpText;
#else
  const std::string keys = "\n(this facet was built without SDL2: the viewer cannot open)";
#endif
  CLI::App* view = app.add_subcommand("view", "Open a model or a demo in a window, orbit it and flip the switches");
  view->footer(keys);
  view->add_option("model", args.model, "Model file (any format facet render reads)")->type_name("MODEL");
  view->add_option("--demo", args.demo, "cube | torus | two-cubes | pentagon, instead of a model")
      ->check(one_of(demo_names()))
      ->type_name("NAME");
  view->add_option("--resolution", args.resolution, "Window size W,H (1280,720)")->type_name("W,H");
  view->add_option("--threads", args.threads, "Render threads; 0 = one per hardware thread (0)")
      ->check(number_in(0, 256, true))
      ->type_name("N");
  view->add_option("--frames", args.frames, "Quit after N frames; the animation then steps 1/60 s a frame")
      ->check(number_in(1, 10000000, true))
      ->type_name("N");
  view->add_option("--keys", args.keys, "Press these keys, in order, before the first frame (e.g. \"w3z\")")
      ->type_name("KEYS");
  view->add_option("--screenshot", args.screenshot, "Write the last frame shown as a PNG")->type_name("FILE.png");
  add_input_options(*view, args.input);
  add_lighting_options(*view, args.look);
  return view;
}

int run_view(const ViewArgs& args) {
  if (args.model.empty() == args.demo.empty()) throw UsageError("view: give a MODEL or --demo NAME, not both");
  const glm::ivec2 size = parse_resolution(args.resolution, "--resolution");
  if (!args.screenshot.empty()) check_output_formats(OutputSpec{.color = args.screenshot});
#if FACET_HAVE_VIEWER
  viewer::ViewerOptions options;
  options.model = args.model;
  if (!args.demo.empty()) options.demo = parse_demo(args.demo);
  options.width = size.x;
  options.height = size.y;
  options.threads = args.threads;
  options.frames = args.frames;
  options.keys = args.keys;
  options.screenshot = args.screenshot;
  options.load = load_options(args.input);
  options.look = look_spec(args.look);
  return viewer::run_viewer(options);
#else
  throw std::runtime_error("view: this facet was built without SDL2 (install libsdl2-dev and rebuild)");
#endif
}

}  // namespace facet::cli
