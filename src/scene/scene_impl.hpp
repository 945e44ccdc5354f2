// scene_impl.hpp - the Scene's state (instances, prepared meshes, textures) and the instances a frame draws.
#pragma once

#include <unordered_map>
#include <vector>

#include "facet/scene.hpp"
#include "scene/draw.hpp"
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
};

namespace detail {
// The frame-wide values the stock shaders share, for one view and set of options.
FrameContext frame_context(const View& view, const SceneOptions& options);
}  // namespace detail

}  // namespace facet
