// render_command.cpp - `facet render`: the flags as a RenderJob, performed by the library.
#include "render_command.hpp"

#include "facet/render_job.hpp"

namespace facet::cli {

CLI::App* add_render_command(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand("render", "Render a model file to a PNG");
  render->add_option("model", args.model, "Model file (.obj, .gltf, .glb, .ply, .stl, or any format Assimp reads)")
      ->required()
      ->type_name("MODEL");
  add_output_options(*render, args.output, "1024,768");
  render
      ->add_option("--output-normal", args.output.output_normal,
                   "Also write camera-space unit normals: float32 H x W x 3, .npy or .exr (0 where empty)")
      ->type_name("FILE.npy");
  render
      ->add_option("--output-ids", args.output.output_ids,
                   "Also write per pixel the instance (node) id and face id: uint32 H x W x 2 .npy "
                   "(4294967295 where empty)")
      ->type_name("FILE.npy");
  render->add_option("--output-mask", args.output.output_mask, "Also write a mask: 8-bit PNG, 255 where drawn")
      ->type_name("FILE.png");
  render
      ->add_option("--output-camera", args.output.output_camera,
                   "Also write the camera as JSON: intrinsics K (OpenCV), poses, near, far")
      ->type_name("FILE.json");
  add_camera_options(*render, args.camera);
  add_look_options(*render, args.look);
  return render;
}

RenderJob render_job(const RenderArgs& args) {
  RenderJob job;
  job.model = args.model;
  const glm::ivec2 size = parse_resolution(args.output.resolution, "--resolution");
  job.width = size.x;
  job.height = size.y;
  job.camera = camera_spec(args.camera);
  job.look = look_spec(args.look);
  job.outputs = {.color = args.output.output,
                 .depth = args.output.output_depth,
                 .normal = args.output.output_normal,
                 .ids = args.output.output_ids,
                 .mask = args.output.output_mask,
                 .camera = args.output.output_camera};
  return job;
}

int run_render(const RenderArgs& args) {
  const RenderJob job = render_job(args);
  Renderer renderer(args.look.threads);
  render(job, renderer);
  return 0;
}

}  // namespace facet::cli
