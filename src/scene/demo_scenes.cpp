// demo_scenes.cpp - the demos of the source documents: their meshes, animations and cameras, as the documents give
// them.
#include "facet/demo_scenes.hpp"

#include <cmath>
#include <cstddef>
#include <span>
#include <string_view>

#include "facet/primitives.hpp"
#include "facet/projection.hpp"
#include "facet/transform.hpp"

namespace facet {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The interleaved buffer exactly as "Barebones 3D rendering with WebGL" gives it (position, rgb; stride 24, offsets
// 0 and 12), read as WebGL would.
Mesh interleaved_cube_mesh() {
  const std::vector<float> data = colored_cube_vertex_data();
  VertexLayout layout;
  layout.stride = 6 * sizeof(float);
  layout.position_offset = 0;
  layout.color_offset = 3 * sizeof(float);
  layout.color_components = 3;
  return mesh_from_interleaved(std::as_bytes(std::span(data)), layout);
}

// The cube of "Computer Graphics from Scratch", converted from the book's left-handed, +Z-forward space to OpenGL's
// by negating z. The mirror keeps each triangle's on-screen winding, so the book's clockwise front faces stay
// clockwise; reversing each triangle makes them counter-clockwise, OpenGL's front.
Mesh two_cubes_mesh() {
  Mesh mesh;
  mesh.positions = {{1, 1, -1}, {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}, {1, 1, 1}, {-1, 1, 1}, {-1, -1, 1}, {1, -1, 1}};
  const glm::vec4 red{1, 0, 0, 1}, green{0, 1, 0, 1}, blue{0, 0, 1, 1}, yellow{1, 1, 0, 1}, purple{1, 0, 1, 1},
      cyan{0, 1, 1, 1};
  const std::uint32_t triangles[12][3] = {{0, 1, 2}, {0, 2, 3}, {1, 5, 6}, {1, 6, 2}, {2, 6, 7}, {2, 7, 3},
                                          {4, 0, 3}, {4, 1, 0}, {4, 3, 7}, {4, 5, 1}, {5, 4, 7}, {5, 7, 6}};
  const glm::vec4 colors[12] = {red, red, yellow, yellow, cyan, cyan, green, purple, green, purple, blue, blue};
  for (int i = 0; i < 12; ++i) {
    mesh.indices.insert(mesh.indices.end(), {triangles[i][0], triangles[i][2], triangles[i][1]});
    mesh.face_colors.push_back(colors[i]);
  }
  validate(mesh, "two-cubes");
  return mesh;
}

// As in "Barebones 3D rendering with WebGL": no camera; the model transform T(0,0,-9) Rx(a) Ry(a) S(2) with
// a = t_ms * pi / 4000, under the glFrustum of near 0.1, far 100, top = near * tan(pi / 8) and right = top * aspect.
DemoFrame rotating_model_frame(const std::shared_ptr<const Mesh>& mesh, double seconds, float aspect) {
  const auto a = static_cast<float>(std::fmod(seconds * kPi / 4.0, 2.0 * kPi));
  DemoFrame frame;
  frame.instances.push_back({mesh, translate({0.0f, 0.0f, -9.0f}) * rotate_x(a) * rotate_y(a) * scale(2.0f)});
  const float n = 0.1f, f = 100.0f, t = n * std::tan(static_cast<float>(kPi) / 8.0f), r = t * aspect;
  frame.view.clip_from_view = frustum(-r, r, -t, t, n, f);
  frame.view.near = n;
  frame.view.far = f;
  return frame;
}

// As in "Computer Graphics from Scratch" (hidden surface removal): camera at (-3, 1, 2) turned -30 degrees about
// Y; instances at (-1.5, 0, 7) scaled 0.75 and at (1.25, 2.5, 7.5) turned 195 degrees; a 1 x 1 viewport at
// distance 1 (vertical view angle 2 atan(1/2)), near plane at 1. Negating z conjugates each of the book's Y
// rotations into OpenGL's rotate_y of the same angle.
DemoFrame two_cubes_frame(const std::shared_ptr<const Mesh>& mesh, float aspect) {
  DemoFrame frame;
  frame.instances.push_back({mesh, translate({-1.5f, 0.0f, -7.0f}) * scale(0.75f)});
  frame.instances.push_back({mesh, translate({1.25f, 2.5f, -7.5f}) * rotate_y(glm::radians(195.0f))});
  // view = (camera orientation)^T * translate(-camera position), as RenderScene builds it.
  frame.view.view_from_world = rotate_y(glm::radians(30.0f)) * translate({3.0f, -1.0f, 2.0f});
  frame.view.near = 1.0f;
  frame.view.far = 100.0f;
  frame.view.clip_from_view = perspective(2.0f * std::atan(0.5f), aspect, frame.view.near, frame.view.far);
  return frame;
}

// The pentagon fan of the CIS367 lecture notes "Building models / Viewing", face on under an orthographic window
// fitted to its unit circumcircle. It turns a fifth of a revolution per second about its normal, so whole seconds
// show it upright.
DemoFrame turning_pentagon_frame(const std::shared_ptr<const Mesh>& mesh, double seconds, float aspect) {
  const auto a = static_cast<float>(std::fmod(seconds * 0.4 * kPi, 2.0 * kPi));
  DemoFrame frame;
  frame.instances.push_back({mesh, rotate_z(a)});
  const float half_h = 1.15f * std::max(1.0f, 1.0f / aspect), half_w = half_h * aspect;
  // The eye sits 2 units in front so the fan's depth (what --output-depth writes) is 2, not the "empty" 0.
  frame.view.view_from_world = translate({0.0f, 0.0f, -2.0f});
  frame.view.near = 1.0f;
  frame.view.far = 3.0f;
  frame.view.clip_from_view = ortho(-half_w, half_w, -half_h, half_h, frame.view.near, frame.view.far);
  return frame;
}

}  // namespace

std::span<const Named<Demo>> demo_names() {
  static constexpr Named<Demo> kNames[] = {
      {"cube", Demo::cube}, {"torus", Demo::torus}, {"two-cubes", Demo::two_cubes}, {"pentagon", Demo::pentagon}};
  return kNames;
}

std::optional<Demo> parse_demo(std::string_view name) { return parse_name(demo_names(), name); }

const char* demo_name(Demo demo) { return name_of(demo_names(), demo); }

DemoModel make_demo(Demo demo) {
  DemoModel model;
  model.demo = demo;
  switch (demo) {
    case Demo::cube: model.mesh = std::make_shared<const Mesh>(interleaved_cube_mesh()); break;
    case Demo::torus:
      model.mesh = std::make_shared<const Mesh>(make_torus(1.0f, 0.4f, 64, 32));
      model.shading = Shading::automatic;  // a one-colour tube only reads as round when lit
      break;
    case Demo::two_cubes: model.mesh = std::make_shared<const Mesh>(two_cubes_mesh()); break;
    case Demo::pentagon: model.mesh = std::make_shared<const Mesh>(make_pentagon()); break;
  }
  return model;
}

DemoFrame demo_frame(const DemoModel& model, double seconds, float aspect) {
  switch (model.demo) {
    case Demo::cube:
    case Demo::torus: return rotating_model_frame(model.mesh, seconds, aspect);
    case Demo::two_cubes: return two_cubes_frame(model.mesh, aspect);
    case Demo::pentagon: return turning_pentagon_frame(model.mesh, seconds, aspect);
  }
  return {};
}

}  // namespace facet
