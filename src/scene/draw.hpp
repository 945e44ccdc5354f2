// draw.hpp - drawing one prepared instance with the stock shaders, given the frame's view, options and lights.
#pragma once

#include <algorithm>
#include <vector>

#include "facet/scene.hpp"
#include "facet/shaders/punctual.hpp"
#include "facet/shaders/surface_color.hpp"
#include "scene/prepared_mesh.hpp"

namespace facet::detail {

struct FrameContext {
  const View* view;
  const SceneOptions* options;
  glm::mat4 clip_from_world;
  glm::vec3 eye;  // world space
  LightBlock lights;                     // the classic shadings'
  std::vector<PunctualLight> punctual;  // the physically based look's
  // Ambient occlusion, 1 open to 0 occluded, per 2 x 2 pixels of the target, top row first, over a region of
  // width x height of them from (x, y) on; nullptr: none.
  const float* occlusion = nullptr;
  int occlusion_x = 0, occlusion_y = 0, occlusion_width = 0, occlusion_height = 0;
};

// The largest factor by which world_from_object stretches a length: scales a bounding sphere's radius.
inline float max_scale(const glm::mat4& m) {
  return std::max({glm::length(glm::vec3(m[0])), glm::length(glm::vec3(m[1])), glm::length(glm::vec3(m[2]))});
}

// The group's material, or the default one (white, Blinn-Phong) for triangles without.
const Material& material_of(const Mesh& mesh, const TriangleGroup& group);
bool is_blended(const Mesh& mesh, const TriangleGroup& group);
// The albedo sources of a group: the material's colour (or the options'), face colours, texture and sampler.
SurfaceColor surface_color(const SceneOptions& options, const Material& material, const PreparedMesh& prepared,
                           const TriangleGroup& group);
// The shading a material is drawn with: the options', or unlit for an unlit material under automatic shading.
Shading shading_of(const SceneOptions& options, const Material& material);
// Whether its fragments below the alpha cutoff are discarded: AlphaMode::mask, under the shadings that have a
// masked pipeline (automatic, Phong, Blinn-Phong, unlit); the others draw it opaque.
bool is_masked(const SceneOptions& options, const Material& material);

// The state a material's surfaces draw with: the options' culling (back faces of single-sided materials culled
// when the options leave it to the model, the culled side swapped for a mirroring instance), and blending for
// AlphaMode::blend. With the depth test off (painter's order or --no-depth) they use "always" rather than no depth
// test: the colours are the same, and the depth buffer still holds the visible surface for edges and depth output.
RenderState surface_state(const SceneOptions& options, const Material& material, bool mirrored);

// A frame draws the opaque surfaces of every instance, each followed by its edges, then the blended surfaces.
enum class DrawPass { opaque, blended };

// One instance's surfaces of that pass, and in the opaque pass its edges or wireframe.
void draw_instance(Renderer& renderer, Framebuffer& target, const FrameContext& frame, const Instance& instance,
                   const PreparedMesh& prepared, DrawPass pass);

// The environment behind everything (SceneOptions::environment_background): one triangle covering the target,
// drawn first, without depth test or depth writes.
void draw_environment_background(Renderer& renderer, Framebuffer& target, const FrameContext& frame);

// The window-depth offset that pulls edge lines in front of the surface they lie on: about two line widths of
// pixel footprint in eye space at the instance's distance, converted through the projection. Negative.
float edge_depth_offset(const glm::mat4& clip_from_view, float distance, float near, float line_width,
                        int target_height, float radius);

}  // namespace facet::detail
