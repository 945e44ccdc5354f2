// main.cpp - a program that uses an installed facet's job layer: renders a model file to a small PNG (and a depth
// buffer when a third argument names one), through the readers and writers facet::render uses.
#include <cstdio>
#include <exception>

#include <facet/render_job.hpp>
#include <facet/renderer.hpp>

int main(int argc, char** argv) {
  if (argc != 3 && argc != 4) {
    std::fprintf(stderr, "usage: %s MODEL OUTPUT.png [DEPTH.exr|.npy]\n", argv[0]);
    return 2;
  }
  try {
    facet::RenderJob job;
    job.model = argv[1];
    job.width = 64;
    job.height = 48;
    job.outputs.color = argv[2];
    if (argc == 4) job.outputs.depth = argv[3];
    facet::Renderer renderer;
    facet::render(job, renderer);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_job: %s\n", e.what());
    return 1;
  }
  return 0;
}
