// camera.hpp - a VTK-style camera (position / focal point / view up), the view it gives, sphere framing and turning
// about the focus.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace facet {

// The camera of VTK / f3d: where it is, what it looks at, which way is up, and its vertical field of view and
// clipping distances (the VTK defaults).
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 1.0f};
  glm::vec3 focal_point{0.0f};
  glm::vec3 view_up{0.0f, 1.0f, 0.0f};
  float view_angle_degrees = 30.0f;  // vertical field of view
  float near = 0.01f, far = 1000.01f;
};

// What a frame is drawn through: the matrices a Camera (or a projection of view_spec.hpp) gives, and the clipping
// distances the depth shading and the depth output read.
struct View {
  glm::mat4 view_from_world{1.0f};
  glm::mat4 clip_from_view{1.0f};
  float near = 0.1f, far = 100.0f;
};

// The bounding sphere a model is framed by: the box centre, and the distance from it to the farthest position.
struct Framing {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// look_at(position, focal_point, view_up); throws like look_at.
glm::mat4 view_from_world(const Camera& camera);

// perspective(view_angle, aspect, near, far); throws like perspective.
glm::mat4 clip_from_view(const Camera& camera, float aspect);

// A camera looking at `center` from `direction` (centre to eye, any length) with `up` as view up, far enough
// that the sphere fits both the vertical view angle and the horizontal one implied by `aspect`, with an 8%
// margin on the tighter of the two. near/far hug the sphere: near = max(d - 1.05 r, 1e-3 d), far = d + 1.05 r.
// view_up is returned orthogonalised against the view direction. Throws std::invalid_argument on a radius that
// is not positive, aspect <= 0, a view angle outside (0, 180), a zero direction, `up` parallel to `direction`,
// or anything non-finite.
Camera frame_sphere(glm::vec3 center, float radius, float aspect, float view_angle_degrees, glm::vec3 direction,
                    glm::vec3 up);

// VTK's Azimuth(azimuth_deg) then Elevation(elevation_deg), as f3d applies them: azimuth turns the position
// about view_up through the focal point (positive moves the camera to its right); elevation turns it about the
// camera's right axis through the focal point (positive moves the camera up, looking down on the scene). Like
// f3d (which calls OrthogonalizeViewUp afterwards), view_up is carried along by the elevation and
// re-orthogonalised, so elevating through the pole does not leave a degenerate camera. The focal point and
// distance are unchanged. Throws std::invalid_argument on non-finite angles or a degenerate camera.
void apply_azimuth_elevation(Camera& camera, float azimuth_deg, float elevation_deg);

}  // namespace facet
