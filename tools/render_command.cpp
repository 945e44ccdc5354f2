// render_command.cpp - `facet render`: the flags as one RenderJob per model, performed by the library.
#include "render_command.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <stdexcept>
#include <utility>

#include "facet/cpu_level.hpp"
#include "facet/error.hpp"
#include "facet/output_template.hpp"
#include "facet/render_job.hpp"

namespace facet::cli {

CLI::App* add_render_command(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand("render", "Render model files to PNG images");
  render
      ->add_option("model", args.models,
                   "Model files (.obj, .gltf, .glb, .ply, .stl, or any format Assimp reads); with several, the "
                   "output names need {model}, {stem} or {n}")
      ->required()
      ->type_name("MODEL...");
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
      ->add_option("--output-motion", args.output.output_motion,
                   "Also write each pixel's motion on the image to the next frame (the animation 1/fps later): "
                   "float32 H x W x 2 in pixels, +x right, +y down, .npy or .exr")
      ->type_name("FILE.npy");
  render
      ->add_option("--output-camera", args.output.output_camera,
                   "Also write the camera as JSON: intrinsics K (OpenCV), poses, near, far")
      ->type_name("FILE.json");
  render
      ->add_option("--views", args.views,
                   "A contact sheet of these views instead of one, e.g. front,top,side,iso (also dimetric, "
                   "trimetric, oblique, one-point, two-point, three-point); --resolution is each view's size")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string {
            try {
              parse_sheet_views(value);
            } catch (const std::invalid_argument& e) {
              return std::string(e.what()).substr(std::string("views: ").size());
            }
            return {};
          },
          "VIEWS"))
      ->type_name("VIEW,...");
  render
      ->add_option(
          "--turntable", args.turntable,
          "Render N frames round the model's up axis, 3 s a turn: --output NAME.gif, .mp4, .webm or {frame} PNGs")
      ->check(number_in(1, kMaxAnimationFrames, true))
      ->type_name("N");
  render
      ->add_option("--animation", args.animation.name,
                   "Pose the model by this animation (glTF), by name or index; see `facet info`. Default: the "
                   "first, when --time or --animate asks for one")
      ->type_name("NAME|INDEX");
  render
      ->add_option("--time", args.animation.time,
                   "Draw the animation this many seconds in (clamped to the clip); with --animate, where it starts")
      ->check(number_in(-1e9, 1e9))
      ->type_name("SECONDS");
  render->add_flag("--animate", args.animation.play,
                   "Render the animation to its end (with --turntable, for N frames while the camera turns): "
                   "--output NAME.gif, .mp4, .webm or {frame} PNGs");
  render->add_option("--fps", args.animation.fps, "Frames a second of --animate (default 30)")
      ->check(number_in(1, kMaxAnimationFps))
      ->type_name("FPS");
  render->add_option("--frames", args.animation.frames, "Frames of --animate, 1/fps apart (default: to the clip's end)")
      ->check(number_in(1, kMaxAnimationFrames, true))
      ->type_name("N");
  render->add_flag("--timings", args.timings,
                   "Print the time of each stage (load, prepare, draw, write), the peak memory and the page faults "
                   "on stderr");
  add_camera_options(*render, args.camera);
  add_look_options(*render, args.look);
  add_input_options(*render, args.input);
  return render;
}

std::vector<RenderJob> render_jobs(const RenderArgs& args, std::size_t first_n) {
  RenderJob base;
  const glm::ivec2 size = parse_resolution(args.output.resolution, "--resolution");
  base.width = size.x;
  base.height = size.y;
  base.camera = camera_spec(args.camera);
  base.look = look_spec(args.look);
  base.samples = args.look.samples;
  if (!args.views.empty()) base.views = parse_sheet_views(args.views);
  base.turntable = args.turntable;
  base.animation = args.animation;
  base.load = load_options(args.input);
  base.load.threads = args.look.threads;
  const std::pair<const char*, const std::string*> outputs[] = {{"--output", &args.output.output},
                                                                {"--output-depth", &args.output.output_depth},
                                                                {"--output-normal", &args.output.output_normal},
                                                                {"--output-ids", &args.output.output_ids},
                                                                {"--output-mask", &args.output.output_mask},
                                                                {"--output-camera", &args.output.output_camera},
                                                                {"--output-motion", &args.output.output_motion}};
  if (args.models.size() > 1)
    for (const auto& [flag, pattern] : outputs)
      if (!pattern->empty() && !template_has(*pattern, "model") && !template_has(*pattern, "stem") &&
          !template_has(*pattern, "n"))
        throw UsageError(std::string(flag) + ": several models need {model}, {stem} or {n} in the file name");

  std::vector<RenderJob> jobs;
  for (std::size_t n = 0; n < args.models.size(); ++n) {
    RenderJob job = base;
    job.model = args.models[n];
    const TemplateValues values{.model = job.model, .n = first_n + n};
    const auto expand = [&](const std::string& pattern) {
      return pattern.empty() ? std::filesystem::path() : std::filesystem::path(expand_template(pattern, values));
    };
    job.outputs = {.color = expand(args.output.output),
                   .depth = expand(args.output.output_depth),
                   .normal = expand(args.output.output_normal),
                   .ids = expand(args.output.output_ids),
                   .mask = expand(args.output.output_mask),
                   .camera = expand(args.output.output_camera),
                   .motion = expand(args.output.output_motion)};
    check_output_formats(job.outputs, job.turntable > 0 || job.animation.play);
    jobs.push_back(std::move(job));
  }
  std::vector<OutputSpec> specs;
  for (const RenderJob& job : jobs) specs.push_back(job.outputs);
  if (const std::optional<OutputClash> clash = find_output_clash(specs))
    throw UsageError("outputs: " + args.models[clash->first] + " and " + args.models[clash->second] +
                     " would both write " + clash->path.string());
  return jobs;
}

namespace {

// One line per render: "facet: timings: MODEL: load 2.1 ms, prepare 0.8 ms, draw 3.9 ms, write 24.6 ms, total 31.4 ms,
// peak memory 48.2 MiB, page faults 4053, avx512" (the process's peak resident memory and its page faults so far:
// pages touched for the first time, which the kernel zeroes, are much of a single render's cost; and the CPU level
// the pipeline ran with, cpu_level()).
void render_timed(const RenderJob& job, Renderer& renderer, bool print) {
  if (!print) return render(job, renderer);
  RenderTimings t;
  render(job, renderer, &t);
  const auto ms = [](double seconds) { return seconds * 1000.0; };
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::fprintf(stderr,
               "facet: timings: %s: load %.1f ms, prepare %.1f ms, draw %.1f ms, write %.1f ms, total %.1f ms, "
               "peak memory %.1f MiB, page faults %ld, %s\n",
               job.model.string().c_str(), ms(t.load), ms(t.prepare), ms(t.draw), ms(t.write),
               ms(t.load + t.prepare + t.draw + t.write), static_cast<double>(usage.ru_maxrss) / 1024.0,
               usage.ru_minflt + usage.ru_majflt, cpu_level());
}

}  // namespace

int run_render(const RenderArgs& args) {
  const std::vector<RenderJob> jobs = render_jobs(args);
  Renderer renderer(args.look.threads);
  if (jobs.size() == 1) {
    render_timed(jobs.front(), renderer, args.timings);
    return 0;
  }
  // Several models: a bad one is reported and the others are still rendered; usage errors stop everything.
  int failed = 0;
  for (const RenderJob& job : jobs) {
    try {
      render_timed(job, renderer, args.timings);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "facet: error: %s\n", e.what());
      ++failed;
    }
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace facet::cli
