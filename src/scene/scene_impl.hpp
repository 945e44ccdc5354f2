// scene_impl.hpp - the Scene's state (instances, prepared meshes, textures) and the instances a frame draws.
#pragma once

#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "facet/scene.hpp"
#include "facet/shaders/shadow_map.hpp"
#include "scene/draw.hpp"
#include "scene/occlusion_kernel.hpp"
#include "scene/prepared_mesh.hpp"

namespace facet {

struct Scene::Impl {
  std::vector<Instance> instances;
  // Keyed by address: the instances hold the meshes alive, so an address cannot be reused while it is a key.
  std::unordered_map<const Mesh*, detail::PreparedMesh> prepared;
  detail::TextureCache textures;

  const detail::PreparedMesh& prepared_of(const Instance& instance) const { return prepared.at(instance.mesh.get()); }

  // The indices of the instances a frame draws, in drawing order: those whose bounding sphere meets the frustum,
  // sorted back to front for the painter's algorithm, else in order of addition.
  std::vector<std::size_t> visible(const detail::FrameContext& frame) const;

  // Of the visible instances, those with blended surfaces, farthest first (by their bounding sphere's centre).
  std::vector<std::size_t> blended(const detail::FrameContext& frame, const std::vector<std::size_t>& visible) const;

  // The view-space z of an instance's bounding sphere centre; more negative is farther.
  float view_z(const detail::FrameContext& frame, std::size_t instance) const;

  // The shadow maps of the last frame that drew shadows, and what they were drawn from.
  struct ShadowCache {
    struct Key {
      int size = 0;
      std::vector<glm::mat4> views;  // each casting light's clip_from_world
      std::vector<std::pair<const Mesh*, glm::mat4>> casters;
      std::optional<glm::vec4> color;
      bool operator==(const Key&) const = default;
    } key;
    std::unique_ptr<Framebuffer> target;
    std::vector<ShadowMap> maps;
  } shadows;

  // The ambient occlusion of the last frame that drew it, at half its resolution (width x height, rounded up): the
  // depth pre-pass, view-space z (0 where nothing is drawn), the raw and the blurred openness (1 open to 0
  // occluded) per pixel.
  struct AmbientOcclusion {
    std::unique_ptr<Framebuffer> target;
    detail::occlusion::Grid z, raw;  // their width and height are the occlusion's
    detail::occlusion::Window window;  // the target's, and the grids' place in it
    std::vector<float> open;
  } occlusion;

  // The radius of a sphere around every instance's bounding sphere. Defined in shadows.cpp.
  float bounding_radius() const;

  // Which surfaces a depth-only pass draws: every one two-sided (what casts shadows), or those a frame shows, with
  // its culling, the blended ones left out (what ambient occlusion sees).
  enum class DepthPass { casters, visible };
  // Draws the depth of every instance that meets clip_from_world's frustum into target, masked materials by their
  // cutoff. Defined in shadows.cpp.
  void draw_depth(Renderer& renderer, Framebuffer& target, const SceneOptions& options,
                  const glm::mat4& clip_from_world, DepthPass pass) const;

  // Fills occlusion for a width x height frame through `view`: screen-space ambient occlusion within `radius`
  // (world units) of each pixel's surface. Defined in ambient_occlusion.cpp.
  void ambient_occlusion(Renderer& renderer, const SceneOptions& options, const View& view, int width, int height,
                         float radius);

  // Points every directional and spot light in `lights` at a size x size shadow map (PunctualLight::shadow),
  // rendering the maps unless the last frame's were drawn from the same lights and instances; point lights stay
  // unshadowed. A directional light's map covers the bounding sphere of every instance, a spot's its cone as far
  // as that sphere reaches. Every surface casts, two-sided, masked materials by their cutoff. The maps live until
  // the next frame that draws shadows. Defined in shadows.cpp.
  void shadow_lights(Renderer& renderer, const SceneOptions& options, std::vector<PunctualLight>& lights, int size);
};

namespace detail {
// The frame-wide values the stock shaders share, for one view and set of options.
FrameContext frame_context(const View& view, const SceneOptions& options);
}  // namespace detail

}  // namespace facet
