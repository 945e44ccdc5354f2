// bench_command.cpp - `facet bench`: parses the BENCHMARK.md flags, renders the timed frames, prints the result line.
#include "bench_command.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_scenes.hpp"
#include "bench/bench_shader.hpp"
#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "facet/renderer.hpp"
#include "facet/texture.hpp"
#include "facet/version.hpp"


namespace facet::bench {
namespace {

const char* const kUsage = R"(usage: facet bench SCENE [options]
Times frames of a benchmark scene (docs/BENCHMARK.md), drawn like the OpenGL reference renderer glref.
scene (exactly one):
  --sphere N          UV sphere, N slices x N stacks, 2N(N-1) triangles (3 <= N <= 4096)
  --quads K           K overlapping screen-filling quads, 2K triangles (1 <= K <= 4096)
    --order b2f|f2b   draw them back to front (default) or front to back
  --mesh PATH         triangle mesh (OBJ), normalised to the unit sphere
options:
  --resolution W,H    target size, each 1 to 16384 (default 1920,1080)
  --frames N          timed frames (default 30)
  --warmup N          frames rendered first and not timed (default 5)
  --threads T         rendering threads, the calling thread included; 0 and 1 mean single-threaded
                      (default: the number of hardware threads)
  --scale S           object scale for sphere and mesh, 0 < S <= 1000 (default 1)
  --png PATH          write frame 0 as PNG (top row = top of screen)
  --depth PATH        write frame 0's window depth as float32 .npy (H x W, top row first, 1.0 where empty)
  --json              print the result as one JSON line on stdout
  --stats             print the pipeline counters of frame 0 on stderr
A repeated option takes its last value. Exit status: 0 ok, 2 bad arguments or unloadable mesh, 1 other failure.
)";

// A bad command line or an unusable mesh: one line on stderr and exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  int sphere = 0, quads = 0, width = 1920, height = 1080, frames = 30, warmup = 5, threads = -1;
  std::string mesh, order = "b2f", png, depth;
  float scale = 1.0f;
  bool json = false, stats = false, help = false;
};

long parse_int(const std::string& flag, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (errno != 0 || text.empty() || *end != '\0' || value < lo || value > hi)
    throw UsageError(flag + " expects an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], got '" + text + "'");
  return value;
}

// Every value is the next argument and a repeated flag takes its last value (compare.sh appends overrides).
Options parse_args(int argc, char** argv) {
  Options o;
  std::string scene_flag;
  bool order_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
      return o;
    }
    if (a == "--json") {
      o.json = true;
      continue;
    }
    if (a == "--stats") {
      o.stats = true;
      continue;
    }
    static const char* const kWithValue[] = {"--sphere", "--quads",   "--mesh",  "--order", "--resolution", "--frames",
                                             "--warmup", "--threads", "--scale", "--png",   "--depth"};
    if (std::find(std::begin(kWithValue), std::end(kWithValue), a) == std::end(kWithValue))
      throw UsageError("unknown option '" + a + "' (see facet bench --help)");
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see facet bench --help)");
    const std::string v = argv[++i];
    if (a == "--sphere" || a == "--quads" || a == "--mesh") {
      if (!scene_flag.empty() && scene_flag != a)
        throw UsageError("choose one scene: " + scene_flag + " and " + a + " both given");
      scene_flag = a;
      if (a == "--sphere") o.sphere = static_cast<int>(parse_int(a, v, 3, 4096));
      else if (a == "--quads") o.quads = static_cast<int>(parse_int(a, v, 1, 4096));
      else if (v.empty()) throw UsageError("--mesh expects a file path, got ''");
      else o.mesh = v;
    } else if (a == "--order") {
      if (v != "b2f" && v != "f2b") throw UsageError("--order expects b2f or f2b, got '" + v + "'");
      o.order = v;
      order_given = true;
    } else if (a == "--resolution") {
      const std::size_t comma = v.find(',');
      if (comma == std::string::npos) throw UsageError("--resolution expects W,H, e.g. 1920,1080, got '" + v + "'");
      o.width = static_cast<int>(parse_int("--resolution width", v.substr(0, comma), 1, kMaxDimension));
      o.height = static_cast<int>(parse_int("--resolution height", v.substr(comma + 1), 1, kMaxDimension));
    } else if (a == "--frames") {
      o.frames = static_cast<int>(parse_int(a, v, 1, 100000));
    } else if (a == "--warmup") {
      o.warmup = static_cast<int>(parse_int(a, v, 0, 100000));
    } else if (a == "--threads") {
      o.threads = static_cast<int>(parse_int(a, v, 0, 1024));
    } else if (a == "--scale") {
      char* end = nullptr;
      o.scale = std::strtof(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !std::isfinite(o.scale) || o.scale <= 0.0f || o.scale > 1000.0f)
        throw UsageError("--scale expects a number in (0, 1000], got '" + v + "'");
    } else if (a == "--png") {
      o.png = v;
    } else {
      o.depth = v;
    }
  }
  if (scene_flag.empty()) throw UsageError("no scene given: use --sphere N, --quads K or --mesh PATH (see --help)");
  if (order_given && o.quads == 0) throw UsageError("--order only applies to --quads");
  if (o.threads < 0) o.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return o;
}

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

// The error line must stay one line whatever the message holds (file names, parser output).
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
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

int run(const Options& o, const BenchGeometry& g) {
  Renderer renderer(std::max(1, o.threads));
  Framebuffer target(o.width, o.height);
  const Texture texture = make_checker_texture(1024);
  BenchShader shader;
  shader.texture = &texture;
  shader.clip_from_world = multiply(projection_matrix(o.width, o.height), view_matrix());
  const RenderState state{};  // back-face culling (CCW front), depth test LESS with writes, no blending
  const std::span<const BenchVertex> vertices(g.vertices);
  const std::span<const std::uint32_t> indices(g.indices);
  const bool keep_frame0 = !o.png.empty() || !o.depth.empty();
  std::vector<std::uint8_t> frame0_rgba;
  std::vector<float> frame0_depth;
  DrawStats frame0_stats;

  std::vector<double> ms;
  ms.reserve(static_cast<std::size_t>(o.frames));
  for (int f = 0; f < o.warmup + o.frames; ++f) {
    shader.set_model(model_matrix(f, o.scale, o.quads != 0));
    const auto t0 = std::chrono::steady_clock::now();
    renderer.clear(target, {0.1f, 0.1f, 0.15f, 1.0f}, 1.0f);
    renderer.draw(target, shader, vertices, indices, state);
    renderer.finish(target);
    const auto t1 = std::chrono::steady_clock::now();
    if (f >= o.warmup) ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (f == 0) {  // after the clock stopped: reading back is not part of a frame
      frame0_stats = renderer.last_stats();
      if (keep_frame0) {
        frame0_rgba = target.rgba8();
        const std::span<const float> depth = std::as_const(target).depth();
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
  if (!o.png.empty()) write_png(o.png, o.width, o.height, frame0_rgba);
  if (!o.depth.empty()) write_npy(o.depth, o.width, o.height, frame0_depth);

  const std::string renderer_name = std::string("facet ") + kVersion;
  const std::size_t triangles = g.indices.size() / 3;
  if (o.json)
    std::printf("{\"renderer\":\"%s\",\"scene\":\"%s\",\"triangles\":%zu,\"width\":%d,\"height\":%d,\"threads\":%d,"
                "\"warmup\":%d,\"frames\":%d,\"median_ms\":%.3f,\"min_ms\":%.3f,\"max_ms\":%.3f}\n",
                json_escape(renderer_name).c_str(), json_escape(g.name).c_str(), triangles, o.width, o.height,
                o.threads, o.warmup, o.frames, t.median, t.min, t.max);
  else
    std::printf("%s  %s  %zu triangles  %dx%d  threads %d  median %.3f ms (min %.3f, max %.3f), %d frames after %d "
                "warm-up\n",
                renderer_name.c_str(), g.name.c_str(), triangles, o.width, o.height, o.threads, t.median, t.min,
                t.max, o.frames, o.warmup);
  return std::fflush(stdout) == 0 ? 0 : 1;
}

}  // namespace

int run_bench(int argc, char** argv) {
  Options options;
  BenchGeometry geometry;
  try {
    options = parse_args(argc, argv);
    if (options.help) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (!options.mesh.empty()) {
      try {
        geometry = load_mesh_scene(options.mesh);
      } catch (const std::bad_alloc&) {
        throw;
      } catch (const std::exception& e) {  // InputError and anything else the loader throws: unusable mesh
        throw UsageError(std::string("cannot load mesh: ") + e.what());
      }
    } else {
      geometry = options.sphere ? make_sphere(options.sphere) : make_quads(options.quads, options.order == "f2b");
    }
  } catch (const UsageError& e) {
    std::fprintf(stderr, "facet: error: %s\n", one_line(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facet: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
  try {
    return run(options, geometry);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facet: error: %s\n", one_line(e.what()).c_str());
    return 1;
  }
}

}  // namespace facet::bench
