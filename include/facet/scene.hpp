// scene.hpp - instances of meshes under one camera, drawn with the stock shaders and drawing modes.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/camera.hpp"
#include "facet/framebuffer.hpp"
#include "facet/light.hpp"
#include "facet/mesh.hpp"
#include "facet/render_state.hpp"
#include "facet/renderer.hpp"
#include "facet/environment.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/texture.hpp"

namespace facet {

enum class Shading {
  automatic,    // the model's own look: its physically based (metallic-roughness) materials, textures and vertex
                // colours lit by the environment and lights, tone-mapped (unlit materials as `unlit`)
  unlit,        // material colour x (vertex colour, else face colour) x texture; no lighting
  flat,         // one lit colour per face (face normal)
  gouraud,      // lit per vertex, colour interpolated
  phong,        // lit per pixel, Phong specular
  blinn_phong,  // lit per pixel, Blinn-Phong specular
  normals,      // world-space normal as colour (n * 0.5 + 0.5)
  depth,        // linear eye-space depth as grey, near = white, far = black
};

struct SceneOptions {
  Shading shading = Shading::automatic;
  // One default light; built with (1) rather than {Light{}} because GCC 12 warns (maybe-uninitialized) about the
  // initializer_list copy at -O2.
  // The physically based look uses every light; the classic shadings the first kMaxLights directional and point
  // lights.
  std::vector<Light> lights = std::vector<Light>(1);
  glm::vec3 ambient{0.15f};
  std::optional<glm::vec4> color;  // overrides every material's diffuse colour (--color)
  CullMode cull = CullMode::back;
  // With cull none: still cull the back faces of materials marked single-sided (glTF doubleSided false), as a
  // glTF viewer does; `facet render` sets it when no --culling is given.
  bool cull_single_sided = false;
  // With depth_test off or painter on, surfaces pass the depth test unconditionally (DepthFunc::always) but still
  // write depth, so edges and linear_depth() see the surface that ended up visible.
  bool depth_test = true;
  bool painter = false;    // sort triangles (and instances) back to front instead of depth-testing them
  bool wireframe = false;  // draw only the edges, in `color` (white if unset), depth-tested among themselves
  bool edges = false;      // draw the surfaces, then each edge once on top (depth-tested with a small offset)
  glm::vec4 edge_color{0.05f, 0.05f, 0.05f, 1.0f};
  float line_width = 1.0f;
  // Points (Mesh::points): their size in pixels and shape. A cloud with normals is lit like a surface; one without
  // is drawn in its colours (vertex colours, or the material's), unlit, unless its material asks for pyrender's
  // lighting (Material::pyrender_lighting), which lights each point as facing the eye.
  float point_size = 2.0f;
  PointShape point_shape = PointShape::square;
  // point_size in world units rather than pixels: each point then covers as much of the image as a square (or
  // disc) of that side would at its distance along the view axis (exact for perspective and orthographic
  // projections), from 1/64 to kMaxPointSize pixels.
  bool world_point_size = false;
  // Eye-dome lighting's strength (0: off): the finished image darkened where the depth steps away from the viewer,
  // the shading point-cloud viewers give clouds without normals or colours (Potree's and Cesium's formula, 8
  // neighbours; see ARCHITECTURE.md). It keeps the target's depth (Framebuffer::keep_depth), sample 0's with several
  // samples. `facet render` turns it on (1) for such a cloud.
  float eye_dome_lighting = 0.0f;
  Sampler sampler{};
  // The physically based look (Shading::automatic): the environment that lights it besides `lights` (none: the
  // ambient colour, as light of that radiance from every direction), and how its light becomes displayed colour.
  std::shared_ptr<const Environment> environment{};
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;
  // Draw the environment behind the model (the physically based look, with an environment), prefiltered at
  // background_blur: a roughness, 0 sharp to 1 the roughest level.
  bool environment_background = false;
  float background_blur = 0.0f;
  // The physically based look: every directional and spot light whose Light::casts_shadows is set casts shadows,
  // from a shadow_map_size² (1..8192) map; point lights and the environment cast none.
  bool shadows = false;
  int shadow_map_size = 1024;
  // The physically based look: screen-space ambient occlusion darkens the environment's and the ambient light in
  // creases and contact, within kOcclusionRadius of the scene's bounding radius of each surface.
  bool ambient_occlusion = false;
};

inline constexpr float kOcclusionRadius = 0.15f;
// SceneOptions::eye_dome_lighting's largest strength, and the one `facet render` gives a cloud without normals or
// colours.
inline constexpr float kMaxEyeDomeLighting = 100.0f;
inline constexpr float kDefaultEyeDomeLighting = 1.0f;

inline constexpr int kMaxLights = 4;
static_assert(kMaxLights <= kLightSlots);

// The first kMaxLights directional and point lights of options.lights (colour times intensity, directions
// normalized) and the ambient term: the classic shadings' lights.
LightBlock make_light_block(const SceneOptions& options);

struct Instance {
  std::shared_ptr<const Mesh> mesh;
  glm::mat4 world_from_object{1.0f};
  bool wireframe = false;  // drawn as its edges, as SceneOptions::wireframe draws every instance
};

// Which surface each pixel shows (Scene::render_ids), top row first; kNoSurface in both where nothing is drawn.
struct SurfaceIds {
  int width = 0, height = 0;
  std::vector<std::uint32_t> instance;  // index into Scene::instances()
  std::vector<std::uint32_t> triangle;  // index of the triangle in that instance's mesh
};

// Holds the per-mesh data the stock shaders read (vertex arrays, face normals and colours, edge lists, textures
// loaded from the materials) so repeated frames do not rebuild it.
class Scene {
 public:
  Scene();
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;

  void add(Instance instance);
  // Moves instance `index` (its place in instances()). Throws std::out_of_range for an index there is none at.
  void set_transform(std::size_t index, const glm::mat4& world_from_object);
  // Removes instance `index`; the later ones move down by one. A mesh's prepared data goes with its last instance.
  // Throws std::out_of_range for an index there is none at.
  void remove(std::size_t index);
  std::size_t size() const;
  const std::vector<Instance>& instances() const;

  // Draws every instance whose bounding sphere meets the view frustum; the others are rejected before any vertex
  // work. Returns how many instances were drawn. Does not clear the framebuffer; ends with Renderer::finish (its
  // draws' shaders read this frame's lights and buffers), so the frame is in `target` when it returns. Gaussian
  // splats (Mesh::splats) are composited after the finish (render_splats); a scene with splats and surfaces turns
  // the target's keep_depth on, so that they composite by depth.
  std::size_t render(Renderer& renderer, Framebuffer& target, const View& view, const SceneOptions& options);

  // Clears target and draws the surfaces as render() would (same instances, culling, depth test and order, no
  // edges or wireframe), recording per pixel which instance and triangle is seen instead of a colour. Leaves
  // target's colour meaningless and its depth that of the surfaces; finishes the frame. A multisampled target keeps
  // its samples from then on (Framebuffer::keep_samples): the ids are sample 0's, never a blend.
  SurfaceIds render_ids(Renderer& renderer, Framebuffer& target, const View& view, const SceneOptions& options);

  // The camera-space (OpenGL axes: x right, y up, z towards the viewer) unit shading normal at each pixel of ids:
  // the mesh's vertex normals (or the normals the scene derived for it) interpolated where the pixel centre's ray
  // meets the triangle, reversed on back faces as the stock shaders light them; (0, 0, 0) where nothing is drawn.
  // ids must come from this scene and view.
  std::vector<glm::vec3> camera_normals(const SurfaceIds& ids, const View& view) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Per pixel of `ids` (from `now` through `view`), how far the surface point under the pixel centre moves on the
// image, in pixels (+x right, +y down), when the scene becomes `later` seen through `later_view`: the point keeps its
// place on its triangle (its barycentric coordinates) and is projected at both moments. `later` holds the same
// instances, in order, of meshes with the same triangles (a clip's next frame, or the same scene through another
// camera). (0, 0) where nothing is drawn, NaN where the point ends behind the eye. What --output-motion writes.
// Throws std::invalid_argument for ids of another size, or scenes that differ in instances or triangles.
std::vector<glm::vec2> screen_motion(const Scene& now, const SurfaceIds& ids, const View& view, const Scene& later,
                                     const View& later_view);

// True when a sphere (world space) lies at least partly inside the frustum of clip_from_world.
bool sphere_in_frustum(const glm::mat4& clip_from_world, glm::vec3 center, float radius);

// Linear eye-space depth (distance along -Z) per pixel, 0 where nothing was drawn (depth buffer at 1), top row
// first: what --output-depth writes. Works for perspective and orthographic projections.
std::vector<float> linear_depth(const Framebuffer& target, const glm::mat4& clip_from_view);
// The same, its rows on the renderer's threads.
std::vector<float> linear_depth(Renderer& renderer, const Framebuffer& target, const glm::mat4& clip_from_view);

}  // namespace facet
