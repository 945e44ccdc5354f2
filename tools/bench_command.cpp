// bench_command.cpp - `facet bench`: the BENCHMARK.md flags, the timed frames and the result line.
#include "bench_command.hpp"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "bench/bench_shader.hpp"
#include "cli_options.hpp"
#include "facet/cpu_level.hpp"
#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "facet/renderer.hpp"
#include "facet/texture.hpp"
#include "facet/version.hpp"

namespace facet::cli {

using bench::BenchGeometry;
using bench::BenchShader;
using bench::BenchVertex;

CLI::App* add_bench_command(CLI::App& app, BenchArgs& args) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Time frames of a benchmark scene (docs/BENCHMARK.md), drawn like the OpenGL reference renderer glref");
  bench->footer(
      "Give exactly one scene. A repeated option takes its last value. Exit status: 0 ok, 2 bad arguments or an "
      "unloadable mesh, 1 any other failure.");
  CLI::Option* sphere = bench->add_option("--sphere", args.sphere, "UV sphere, N slices x N stacks, 2N(N-1) triangles")
                            ->check(number_in(3, 4096, true))
                            ->type_name("N");
  CLI::Option* quads = bench->add_option("--quads", args.quads, "K overlapping screen-filling quads, 2K triangles")
                           ->check(number_in(1, 4096, true))
                           ->type_name("K");
  CLI::Option* mesh =
      bench->add_option("--mesh", args.mesh, "Triangle mesh (any format facet reads), unit-sphere sized")
          ->check(
              CLI::Validator([](std::string& v) { return v.empty() ? std::string("expects a file path") : ""; }, ""))
          ->type_name("PATH");
  sphere->excludes(quads)->excludes(mesh);
  quads->excludes(mesh);
  bench->add_option("--order", args.order, "Draw the quads back to front (b2f, default) or front to back (f2b)")
      ->check(CLI::IsMember({"b2f", "f2b"}))
      ->needs(quads);
  bench->add_option("--resolution", args.resolution, "Target size W,H, each 1 to 16384 (default 1920,1080)")
      ->check(parse_check([](const std::string& v) { parse_resolution(v, "--resolution"); }, ""))
      ->type_name("W,H");
  bench->add_option("--frames", args.frames, "Timed frames (default 30)")->check(number_in(1, 100000, true));
  bench->add_option("--warmup", args.warmup, "Frames rendered first and not timed (default 5)")
      ->check(number_in(0, 100000, true));
  bench
      ->add_option("--threads", args.threads,
                   "Rendering threads, the calling thread included; 0 and 1 mean one (default: hardware threads)")
      ->check(number_in(0, 1024, true));
  // 0 < S: the smallest normal float is the least value that does not round to zero on the way to float.
  bench->add_option("--samples", args.samples, "Samples per pixel: 1, 2, 4 or 8 (multisampling; default 1)")
      ->check(CLI::IsMember({1, 2, 4, 8}))
      ->type_name("N");
  bench->add_option("--scale", args.scale, "Object scale of the sphere and the mesh, 0 < S <= 1000 (default 1)")
      ->check(number_in(FLT_MIN, 1000.0));
  bench->add_option("--png", args.png, "Write frame 0 as PNG (top row = top of screen)")->type_name("PATH");
  bench->add_option("--depth", args.depth, "Write frame 0's window depth as float32 .npy (H x W, 1.0 where empty)")
      ->type_name("PATH");
  bench->add_flag("--json", args.json, "Print the result as one JSON line on stdout");
  bench->add_flag("--stats", args.stats, "Print the pipeline counters of frame 0 on stderr");
  // compare.sh appends overrides (--warmup 0 --frames 1 --png ...) to the flags it was given.
  for (CLI::Option* option : bench->get_options()) option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  return bench;
}

namespace {

std::string json_escape(const std::string& s) {
  std::string r;
  for (const unsigned char c : s) {
    if (c == '"' || c == '\\') {
      r += '\\';
      r += static_cast<char>(c);
    } else if (c < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
      r += buffer;
    } else {
      r += static_cast<char>(c);
    }
  }
  return r;
}

struct Timings {
  double median = 0, min = 0, max = 0;
};

Timings summarize(std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  const double median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  return {median, ms.front(), ms.back()};
}

int run(const BenchArgs& o, int width, int height, int threads, const BenchGeometry& g) {
  Renderer renderer(std::max(1, threads));
  Framebuffer target(width, height, o.samples);
  const Texture texture = make_checker_texture(1024);
  BenchShader shader;
  shader.texture = &texture;
  shader.clip_from_world = bench::multiply(bench::projection_matrix(width, height), bench::view_matrix());
  RenderState state{};  // back-face culling (CCW front), depth test LESS with writes, no blending
  state.point_size = bench::kBenchPointSize;
  const std::span<const BenchVertex> vertices(g.vertices);
  const std::span<const std::uint32_t> indices(g.indices);
  const bool keep_frame0 = !o.png.empty() || !o.depth.empty();
  std::vector<std::uint8_t> frame0_rgba;
  std::vector<float> frame0_depth;
  DrawStats frame0_stats;

  std::vector<double> ms;
  ms.reserve(static_cast<std::size_t>(o.frames));
  for (int f = 0; f < o.warmup + o.frames; ++f) {
    shader.set_model(bench::model_matrix(f, o.scale, o.quads != 0));
    const auto t0 = std::chrono::steady_clock::now();
    renderer.clear(target, {0.1f, 0.1f, 0.15f, 1.0f}, 1.0f);
    if (g.points) renderer.draw_points(target, shader, vertices, indices, state);
    else renderer.draw(target, shader, vertices, indices, state);
    renderer.finish(target);
    const auto t1 = std::chrono::steady_clock::now();
    if (f >= o.warmup) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (f == 0) {  // after the clock stopped: reading back is not part of a frame
      frame0_stats = renderer.last_stats();
      if (keep_frame0) {
        frame0_rgba = target.rgba8();
        const std::span<const float> depth = target.depth();
        frame0_depth.assign(depth.begin(), depth.end());
      }
    }
  }
  const Timings t = summarize(ms);

  if (o.stats)
    std::fprintf(stderr,
                 "facet: frame 0 statistics: primitives=%zu culled=%zu clipped=%zu invalid=%zu binned=%zu "
                 "vertices_shaded=%zu vertices_held=%zu\n",
                 frame0_stats.primitives, frame0_stats.culled, frame0_stats.clipped, frame0_stats.invalid,
                 frame0_stats.binned, frame0_stats.vertices_shaded, frame0_stats.vertices_held);
  if (!o.png.empty()) write_png(o.png, width, height, frame0_rgba);
  if (!o.depth.empty()) write_npy(o.depth, width, height, frame0_depth);

  const std::string renderer_name = std::string("facet ") + kVersion;
  // A point cloud reports its points where a mesh reports triangles ("points" in JSON).
  const char* primitive = g.points ? "points" : "triangles";
  const std::size_t count = g.points ? g.indices.size() : g.indices.size() / 3;
  const std::string samples_field = o.samples > 1 ? ",\"samples\":" + std::to_string(o.samples) : "";
  const std::string samples_text = o.samples > 1 ? "  samples " + std::to_string(o.samples) : "";
  if (o.json)
    std::printf(
        "{\"renderer\":\"%s\",\"scene\":\"%s\",\"%s\":%zu,\"width\":%d,\"height\":%d,\"threads\":%d,"
        "\"warmup\":%d,\"frames\":%d,\"median_ms\":%.3f,\"min_ms\":%.3f,\"max_ms\":%.3f%s,\"isa\":\"%s\"}\n",
        json_escape(renderer_name).c_str(), json_escape(g.name).c_str(), primitive, count, width, height, threads,
        o.warmup,
        o.frames, t.median, t.min, t.max, samples_field.c_str(), cpu_level());
  else
    std::printf(
        "%s  %s  %zu %s  %dx%d  threads %d%s  median %.3f ms (min %.3f, max %.3f), %d frames after %d "
        "warm-up, %s\n",
        renderer_name.c_str(), g.name.c_str(), count, primitive, width, height, threads, samples_text.c_str(), t.median,
        t.min,
        t.max, o.frames, o.warmup, cpu_level());
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int run_bench(const BenchArgs& args) {
  if (args.sphere == 0 && args.quads == 0 && args.mesh.empty())
    throw UsageError("no scene given: use --sphere N, --quads K or --mesh PATH (see facet bench --help)");
  const glm::ivec2 size = parse_resolution(args.resolution, "--resolution");
  const int threads =
      args.threads >= 0 ? args.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  BenchGeometry geometry;
  if (!args.mesh.empty()) {
    try {
      geometry = bench::load_mesh_scene(args.mesh);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {  // InputError and anything else the loader throws: an unusable mesh
      throw UsageError(std::string("cannot load mesh: ") + e.what());
    }
  } else {
    geometry = args.sphere ? bench::make_sphere(args.sphere) : bench::make_quads(args.quads, args.order == "f2b");
  }
  return run(args, size.x, size.y, threads, geometry);
}

}  // namespace facet::cli
