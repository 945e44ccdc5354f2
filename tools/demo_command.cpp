// demo_command.cpp - `facet demo`: the rotating cube and torus, the two cubes and the pentagon fan of the tutorials.
#include "demo_command.hpp"

#include "facet/demo_scenes.hpp"
#include "facet/render_job.hpp"

namespace facet::cli {

CLI::App* add_demo_command(CLI::App& app, DemoArgs& args) {
  CLI::App* demo = app.add_subcommand("demo", "Render a built-in demo scene, one frame or an animation");
  demo->add_option("scene", args.name,
                   "cube | torus (spinning), two-cubes (two cubes seen at an angle), pentagon (a turning triangle fan)")
      ->required()
      ->check(one_of(demo_names()))
      ->type_name("SCENE");
  add_output_options(*demo, args.output, "800,800");
  demo->add_option("--time", args.time, "Moment of the animation in seconds")
      ->capture_default_str()
      ->check(number_in(-1e6, 1e6))
      ->type_name("SECONDS");
  demo->add_option(
          "--frames", args.frames,
          "Write N frames 1/30 s apart: an animation (NAME.gif, .mp4, .webm) or PNG frames named with {frame:04}")
      ->check(number_in(1, kMaxAnimationFrames, true))
      ->type_name("N");
  add_look_options(*demo, args.look);
  return demo;
}

int run_demo(const DemoArgs& args) {
  const glm::ivec2 size = parse_resolution(args.output.resolution, "--resolution");
  RenderJob job;
  job.demo = parse_demo(args.name);
  job.time = args.time;
  job.frames = args.frames;
  job.width = size.x;
  job.height = size.y;
  job.look = look_spec(args.look);
  job.samples = args.look.samples;
  const OutputArgs& o = args.output;
  job.outputs = {.color = o.output,
                 .depth = o.output_depth,
                 .normal = o.output_normal,
                 .ids = o.output_ids,
                 .mask = o.output_mask,
                 .camera = o.output_camera};
  Renderer renderer(args.look.threads);
  render(job, renderer);
  return 0;
}

}  // namespace facet::cli
