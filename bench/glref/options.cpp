// options.cpp - reads the contract's flags: each value is the next argument, a repeated flag keeps its last value.
#include "options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>

namespace glref {
namespace {

constexpr const char* kUsage =
    "usage: glref (--sphere N | --quads K [--order b2f|f2b] | --mesh PATH) [--resolution W,H] [--frames N]\n"
    "             [--warmup N] [--threads T] [--scale S] [--samples 1|2|4|8] [--png PATH] [--depth PATH]\n"
    "             [--json] [--stats]\n"
    "Draws the benchmark scene with OpenGL on Mesa's llvmpipe (EGL, no display) and times its frames.\n";

const std::set<std::string> kValueFlags = {"--sphere",  "--quads",   "--order", "--mesh",  "--resolution", "--frames",
                                           "--warmup",  "--threads", "--scale", "--samples", "--png",     "--depth"};

[[noreturn]] void bad(const std::string& message) {
  std::fprintf(stderr, "glref: %s\n", message.c_str());
  std::exit(2);
}

long integer(const std::string& flag, const char* text, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno || end == text || *end || v < lo || v > hi)
    bad(flag + " needs an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got '" + text + "'");
  return v;
}

}  // namespace

Options parse_options(int argc, char** argv) {
  Options o;
  int scenes = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    }
    if (flag == "--json" || flag == "--stats") {
      (flag == "--json" ? o.json : o.stats) = true;
      continue;
    }
    if (!kValueFlags.contains(flag)) bad("unknown option '" + flag + "' (see --help)");
    if (i + 1 >= argc) bad(flag + " needs a value");
    const char* value = argv[++i];
    if (flag == "--sphere" || flag == "--quads") {
      const SceneKind kind = flag == "--sphere" ? SceneKind::sphere : SceneKind::quads;
      if (o.scene != kind) ++scenes;
      o.scene = kind;
      o.count = static_cast<int>(kind == SceneKind::sphere ? integer(flag, value, 3, 4096) : integer(flag, value, 1, 4096));
    } else if (flag == "--mesh") {
      if (o.scene != SceneKind::mesh) ++scenes;
      o.scene = SceneKind::mesh;
      o.mesh = value;
    } else if (flag == "--order") {
      const std::string order = value;
      if (order != "b2f" && order != "f2b") bad("--order is b2f or f2b, got '" + order + "'");
      o.front_to_back = order == "f2b";
      o.order_given = true;
    } else if (flag == "--resolution") {
      const std::string v = value;
      const std::size_t comma = v.find(',');
      if (comma == std::string::npos) bad("--resolution needs W,H, got '" + v + "'");
      o.width = static_cast<int>(integer("--resolution", v.substr(0, comma).c_str(), 1, 16384));
      o.height = static_cast<int>(integer("--resolution", v.substr(comma + 1).c_str(), 1, 16384));
    } else if (flag == "--frames") {
      o.frames = static_cast<int>(integer(flag, value, 1, 1000000));
    } else if (flag == "--warmup") {
      o.warmup = static_cast<int>(integer(flag, value, 0, 1000000));
    } else if (flag == "--threads") {
      o.threads = static_cast<int>(integer(flag, value, 0, 1024));
    } else if (flag == "--samples") {
      o.samples = static_cast<int>(integer(flag, value, 1, 8));
      if (o.samples != 1 && o.samples != 2 && o.samples != 4 && o.samples != 8)
        bad("--samples is 1, 2, 4 or 8, got '" + std::string(value) + "'");
    } else if (flag == "--scale") {
      char* end = nullptr;
      o.scale = std::strtof(value, &end);
      if (end == value || *end || !std::isfinite(o.scale) || o.scale <= 0 || o.scale > 1000)
        bad("--scale needs a number in (0, 1000], got '" + std::string(value) + "'");
    } else if (flag == "--png") {
      o.png = value;
    } else if (flag == "--depth") {
      o.depth = value;
    }
  }
  if (scenes != 1) bad("give exactly one of --sphere, --quads and --mesh");
  if (o.order_given && o.scene != SceneKind::quads) bad("--order goes with --quads only");
  return o;
}

}  // namespace glref
