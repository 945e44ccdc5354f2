// options.hpp - the benchmark scene contract's command line, as the OpenGL reference reads it.
#pragma once

#include <string>

namespace glref {

enum class SceneKind { none, sphere, quads, mesh };

struct Options {
  SceneKind scene = SceneKind::none;
  int count = 0;  // the sphere's N or the quads' K
  bool front_to_back = false;
  bool order_given = false;
  std::string mesh;
  int width = 1920, height = 1080;
  int frames = 30, warmup = 5;
  int threads = -1;  // -1: $LP_NUM_THREADS, else the CPU count
  float scale = 1.0f;
  int samples = 1;
  std::string png, depth;  // frame 0's image and depth (.npy), when given
  bool json = false;
  bool stats = false;  // frame 0's samples passed and primitives generated, on stderr
};

// The options of argv, or a one-line error on stderr and exit status 2 (the contract's rule for bad arguments).
Options parse_options(int argc, char** argv);

}  // namespace glref
