// render_command.hpp - `facet render MODEL --output out.png`, and the look + draw + write step `facet demo` shares.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "cli_options.hpp"

namespace facet::cli {

struct RenderArgs {
  std::string model;
  CameraArgs camera;
  LookArgs look;
  OutputArgs output;
};

// Adds the `render` subcommand, filling `args` when it is parsed.
CLI::App* add_render_command(CLI::App& app, RenderArgs& args);

// Runs it; throws InputError for bad input, UsageError or std::invalid_argument for bad usage.
int run_render(const RenderArgs& args);

// SceneOptions from the look flags. `view_from_world` places the default light (a headlight above and to the left
// of the camera) in the world; `default_shading` applies when --shading is not given.
SceneOptions make_scene_options(const LookArgs& args, const glm::mat4& view_from_world, Shading default_shading,
                                glm::vec3 background);

// --color replaces the materials' colours, and the per-vertex and per-face colours too (the shaders prefer those
// over the material), so the whole model takes the colour asked for.
void apply_color_override(Mesh& mesh, const LookArgs& args);

// The clear colour: --background-color (or `fallback`), alpha 0 with --no-background.
glm::vec4 clear_color(const LookArgs& args, glm::vec3 fallback);

// Clears, draws the scene, writes the PNG (RGBA with --no-background, else RGB) and, when depth_path is not empty,
// the linear depth as .npy. If the depth file cannot be written the PNG is removed again, so a failed run leaves
// neither file behind.
void draw_and_write(Renderer& renderer, Framebuffer& target, Scene& scene, const View& view,
                    const SceneOptions& options, glm::vec4 clear, const std::string& color_path,
                    const std::string& depth_path);

}  // namespace facet::cli
