// main.cpp - a program that uses an installed facet: renders a lit torus to the PNG named on the command line.
#include <cstdio>
#include <exception>
#include <memory>

#include <facet/camera.hpp>
#include <facet/framebuffer.hpp>
#include <facet/image_io.hpp>
#include <facet/primitives.hpp>
#include <facet/renderer.hpp>
#include <facet/scene.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT.png\n", argv[0]);
    return 2;
  }
  try {
    constexpr int width = 320, height = 240;
    facet::Scene scene;
    scene.add({std::make_shared<const facet::Mesh>(facet::make_torus(1.0f, 0.4f, 48, 24)), glm::mat4(1.0f)});

    const float aspect = static_cast<float>(width) / height;
    const facet::Camera camera = facet::frame_sphere(glm::vec3(0.0f), 1.4f, aspect, 30.0f, {0, 1, 2}, {0, 1, 0});
    const facet::View view{facet::view_from_world(camera), facet::clip_from_view(camera, aspect), camera.near,
                           camera.far};

    facet::Renderer renderer;
    facet::Framebuffer target(width, height);
    renderer.clear(target, {0.1f, 0.1f, 0.15f, 1.0f});
    scene.render(renderer, target, view, facet::SceneOptions{});
    renderer.finish(target);
    facet::write_png(argv[1], target);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
