// eye_dome_lighting.hpp - eye-dome lighting, the screen-space shading of point clouds without normals or colours.
#pragma once

#include <glm/mat4x4.hpp>

namespace facet {
class Framebuffer;
class Renderer;
}  // namespace facet

namespace facet::detail {

// Darkens each drawn pixel of target's finished frame by how far its neighbours stand out towards the viewer
// (SceneOptions::eye_dome_lighting): target must have kept its depth (sample 0's with several samples).
void apply_eye_dome_lighting(Renderer& renderer, Framebuffer& target, const glm::mat4& clip_from_view, float strength);

}  // namespace facet::detail
