// demo_command.cpp - `facet demo`: the rotating cube and torus, the two cubes and the pentagon fan of the tutorials.
#include "demo_command.hpp"

#include <filesystem>
#include <memory>
#include <string>

#include "facet/demo_scenes.hpp"
#include "facet/image_io.hpp"
#include "facet/output_template.hpp"
#include "facet/render_job.hpp"
#include "render_command.hpp"

namespace facet::cli {

CLI::App* add_demo_command(CLI::App& app, DemoArgs& args) {
  CLI::App* demo = app.add_subcommand("demo", "Render a built-in demo scene, one frame or an animation");
  demo->add_option("scene", args.name,
                   "cube | torus (spinning), two-cubes (two cubes seen at an angle), pentagon (a turning triangle fan)")
      ->required()
      ->check(one_of(demo_names()))
      ->type_name("SCENE");
  add_output_options(*demo, args.output, "800,800");
  demo->add_option("--time", args.time, "Moment of the animation in seconds (1)")
      ->check(number_in(-1e6, 1e6))
      ->type_name("SECONDS");
  demo->add_option(
          "--frames", args.frames,
          "Write N frames 1/30 s apart: an animation (NAME.gif, .mp4, .webm) or PNG frames named with {frame:04}")
      ->check(number_in(1, 100000, true))
      ->type_name("N");
  add_look_options(*demo, args.look);
  return demo;
}

int run_demo(const DemoArgs& args) {
  const glm::ivec2 size = parse_resolution(args.output.resolution, "--resolution");
  const bool animation = is_animation_path(args.output.output);
  if (!animation && !template_has(args.output.output, "frame") && args.frames > 1)
    throw UsageError("--output: --frames needs a .gif, .mp4 or .webm name, or {frame} or {frame:04} in the file name");
  if (animation && !args.output.output_depth.empty())
    throw UsageError("--output-depth: an animation has no depth output");
  check_output_formats(OutputSpec{.color = args.output.output}, animation);
  if (!args.output.output_depth.empty() && !template_has(args.output.output_depth, "frame") && args.frames > 1)
    throw UsageError("--output-depth: --frames needs {frame} or {frame:04} in the file name");

  DemoModel demo = make_demo(*parse_demo(args.name));
  const LookSpec look = look_spec(args.look);
  if (look.color) {
    Mesh recoloured = *demo.mesh;
    apply_look_color(recoloured, look);
    demo.mesh = std::make_shared<const Mesh>(std::move(recoloured));
  }

  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
  const glm::vec4 clear = clear_color(look, demo.background);
  Renderer renderer(args.look.threads);
  Framebuffer target(size.x, size.y, args.look.samples);
  std::vector<std::vector<std::uint8_t>> frames;  // an animation's, encoded together at the end
  for (int i = 0; i < args.frames; ++i) {
    DemoFrame frame = demo_frame(demo, args.time + i / 30.0, aspect);
    Scene scene;
    for (Instance& instance : frame.instances) scene.add(std::move(instance));
    const SceneOptions options = scene_options(look, frame.view.view_from_world, demo.shading, glm::vec3(clear));
    if (animation) {
      FrameBuffers buffers = draw_buffers(renderer, target, scene, frame.view, options, clear, BufferRequest{});
      frames.push_back(std::move(buffers.color));
      continue;
    }
    const TemplateValues values{.frame = i};
    const std::string depth_path =
        args.output.output_depth.empty() ? std::string() : expand_template(args.output.output_depth, values);
    draw_and_write(renderer, target, scene, frame.view, options, clear,
                   {.color = expand_template(args.output.output, values), .depth = depth_path});
  }
  if (animation) write_animation(args.output.output, size.x, size.y, frames, 1.0 / 30.0);  // as the frames are spaced
  return 0;
}

}  // namespace facet::cli
