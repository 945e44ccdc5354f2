// scene_frame_bench.cpp - one scene frame through the C++ library (colour and depth read back), timed per round;
// the C++ side of bench/python_bench.py, which renders the same model and view through the Python package.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <string>

#include "facet/model_io.hpp"
#include "facet/projection.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/transform.hpp"

// Usage: facet_scene_frame_bench MODEL WIDTH HEIGHT FRAMES THREADS. Prints the mean milliseconds per frame of
// FRAMES frames, each cleared, drawn and read back as colour (RGB) and depth arrays, after one warm-up frame. The
// view is python_bench.py's: eye (0, 0, 3) looking at the origin, a 0.8 rad vertical field of view, near 0.5,
// far 10, back faces culled, the default headlight and ambient of a facet.Scene.
int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: %s MODEL WIDTH HEIGHT FRAMES THREADS\n", argv[0]);
    return 2;
  }
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]), frames = std::atoi(argv[4]);
  facet::Renderer renderer(std::atoi(argv[5]));
  facet::Scene scene;
  scene.add({std::make_shared<const facet::Mesh>(facet::load_model(argv[1])), glm::mat4(1.0f)});
  facet::View view;
  view.view_from_world = facet::look_at(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
  view.clip_from_view = facet::perspective(0.8f, static_cast<float>(width) / static_cast<float>(height), 0.5f, 10.0f);
  view.near = 0.5f;
  view.far = 10.0f;
  facet::SceneOptions options;
  options.cull = facet::CullMode::back;
  options.lights = {facet::Light{facet::Light::Kind::directional, glm::vec3(-0.3f, 0.5f, 0.8f), glm::vec3(1.0f), 1.0f}};
  facet::Framebuffer target(width, height);
  const facet::BufferRequest request{.color = false, .depth = true};
  std::size_t checksum = 0;
  const auto frame = [&] {
    facet::FrameBuffers out = facet::draw_buffers(renderer, target, scene, view, options, glm::vec4(0.0f), request);
    // The RGB array Python returns, read as the Python module reads it: straight from the framebuffer's pixels.
    const std::span<const std::uint32_t> pixels = target.color();
    std::vector<std::uint8_t> rgb(pixels.size() * 3);
    for (std::size_t i = 0; i < pixels.size(); ++i)
      for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = static_cast<std::uint8_t>(pixels[i] >> (8 * c));
    const std::size_t centre = static_cast<std::size_t>(height / 2) * width + width / 2;
    checksum += rgb[3 * centre] + static_cast<std::size_t>(out.depth[centre] > 0.0f);
  };
  frame();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) frame();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("%.4f\n", ms / frames);
  return checksum == 0 ? 1 : 0;  // nothing drawn at the centre: the frames timed were not the ones meant
}
