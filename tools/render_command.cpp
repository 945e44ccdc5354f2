// render_command.cpp - `facet render` (model -> bounding sphere -> View -> PNG, depth .npy) and the shared draw step.
#include "render_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <system_error>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"

namespace facet::cli {
namespace {

// The default background: a mid blue-grey that both white and dark models stand out from.
constexpr glm::vec3 kBackground{0.42f, 0.45f, 0.5f};

}  // namespace

CLI::App* add_render_command(CLI::App& app, RenderArgs& args) {
  CLI::App* render = app.add_subcommand("render", "Render a model (Wavefront OBJ) to a PNG");
  render->add_option("model", args.model, "Model file (.obj)")->required()->type_name("MODEL");
  add_output_options(*render, args.output, "1024,768");
  add_camera_options(*render, args.camera);
  add_look_options(*render, args.look);
  return render;
}

int run_render(const RenderArgs& args) {
  const glm::ivec2 size = parse_resolution(args.output.resolution, "--resolution");
  if (!args.output.output_depth.empty() && std::filesystem::path(args.output.output_depth).lexically_normal() ==
                                               std::filesystem::path(args.output.output).lexically_normal())
    throw UsageError("--output-depth: must differ from --output");

  auto mesh = std::make_shared<Mesh>(load_model(args.model));
  apply_color_override(*mesh, args.look);
  const Bounds box = bounds(*mesh);
  const glm::vec3 center = box.center();
  // The sphere about the box centre through the farthest vertex: at most the box's half diagonal, and often much
  // tighter, so the model fills more of the frame.
  float radius = 0.0f;
  for (const glm::vec3& p : mesh->positions) radius = std::max(radius, glm::distance(p, center));
  // Coordinates near the float limit overflow the camera distance; such a model cannot be framed.
  if (!std::isfinite(radius) || !std::isfinite(glm::length(center)) || radius > 1e30f)
    throw InputError(args.model, "coordinates too large to frame (bounding radius " + std::to_string(radius) + ")");

  const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
  const View view = make_view(args.camera, center, radius, aspect);
  const glm::vec4 clear = clear_color(args.look, kBackground);
  const SceneOptions options =
      make_scene_options(args.look, view.view_from_world, Shading::automatic, glm::vec3(clear));

  Scene scene;
  scene.add(Instance{mesh, glm::mat4(1.0f)});
  Renderer renderer(args.look.threads);
  Framebuffer target(size.x, size.y);
  draw_and_write(renderer, target, scene, view, options, clear, args.output.output, args.output.output_depth);
  return 0;
}

SceneOptions make_scene_options(const LookArgs& args, const glm::mat4& view_from_world, Shading default_shading,
                                glm::vec3 background) {
  SceneOptions options;
  options.shading = args.shading.value_or(default_shading);
  glm::vec3 light;
  if (!args.light_direction.empty()) {
    light = parse_vec3(args.light_direction, "--light-direction");
  } else {
    // A headlight fixed to the camera, from above left as in illustrations, lights whatever side the camera looks
    // at and gives the three faces of a box seen in a 3/4 view three distinct tones.
    light = glm::transpose(glm::mat3(view_from_world)) * glm::vec3(-0.3f, 0.5f, 0.8f);
  }
  options.lights = {Light{Light::Kind::directional, light, glm::vec3(1.0f), 1.0f}};
  if (!args.color.empty()) options.color = glm::vec4(parse_color(args.color, "--color"), 1.0f);
  options.cull = args.culling.value_or(CullMode::back);
  options.depth_test = !args.no_depth_test;
  options.painter = args.painter;
  options.wireframe = args.wireframe;
  options.edges = args.edges;
  // Wireframe lines take --color, else white; on a light background white lines would vanish.
  const float luminance = glm::dot(background, glm::vec3(0.2126f, 0.7152f, 0.0722f));
  if (args.wireframe && !options.color && luminance > 0.5f) options.color = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);
  return options;
}

void apply_color_override(Mesh& mesh, const LookArgs& args) {
  if (args.color.empty()) return;
  mesh.colors.clear();
  mesh.face_colors.clear();
}

glm::vec4 clear_color(const LookArgs& args, glm::vec3 fallback) {
  const glm::vec3 rgb =
      args.background_color.empty() ? fallback : parse_color(args.background_color, "--background-color");
  return {rgb, args.no_background ? 0.0f : 1.0f};
}

void draw_and_write(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                    const SceneOptions& options, glm::vec4 clear, const std::string& color_path,
                    const std::string& depth_path) {
  renderer.clear(target, clear, 1.0f);
  scene.render(renderer, target, view, options);
  renderer.finish(target);
  write_png(color_path, target, clear.a < 1.0f);
  if (depth_path.empty()) return;
  try {
    const std::vector<float> depth = linear_depth(target, view.clip_from_view);
    write_npy(depth_path, target.width(), target.height(), depth);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(color_path, ignored);
    throw;
  }
}

}  // namespace facet::cli
