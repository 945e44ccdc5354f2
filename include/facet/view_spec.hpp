// view_spec.hpp - the camera as a user states it (framing, position, angles, up axis, projection) and its View.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "facet/camera.hpp"
#include "facet/mesh.hpp"

namespace facet {

// Perspective and the classical projections; the view presets (isometric onwards) fix the viewing direction.
enum class Projection {
  perspective,   // gluPerspective with the view angle
  orthographic,  // glOrtho, fitted to the model unless a window is given
  frustum,       // glFrustum with a near-plane window
  oblique,       // cabinet or cavalier: ortho times a shear, seen from the front
  isometric,
  dimetric,
  trimetric,
  front,
  top,
  side,
};

// The model's up axis, which the default views keep vertical on screen.
enum class UpAxis { pos_x, neg_x, pos_y, neg_y, pos_z, neg_z };

// "+Y", "-z", "Z" (a bare letter is positive), ...; nullopt for anything else.
std::optional<UpAxis> parse_up_axis(std::string_view text);

// The rotation taking the model's up axis to +Y.
glm::mat3 upright_from_model(UpAxis up);

// Every field defaults to what `facet render` does with no camera flags: a 3/4 view from the front right, above,
// framing the model's bounding sphere with an 8% margin. The spelling follows f3d's camera options.
struct CameraSpec {
  std::optional<glm::vec3> position;     // the eye; default: framed (ignored by the view presets)
  std::optional<glm::vec3> focal_point;  // the point looked at; default: the model's centre
  std::optional<glm::vec3> view_up;      // default: the model's up axis
  float view_angle_degrees = 30.0f;      // vertical field of view (VTK's and f3d's default)
  float azimuth_degrees = 0.0f;          // turns the camera about view up (VTK's Azimuth), after framing
  float elevation_degrees = 0.0f;        // lifts it (VTK's Elevation)
  std::optional<float> near, far;        // clipping distances; default: hug the model
  Projection projection = Projection::perspective;
  std::optional<std::array<float, 4>> frustum_window;  // L, R, B, T at the near plane (frustum)
  std::optional<std::array<float, 4>> ortho_window;    // L, R, B, T (orthographic, oblique, presets); default: fit
  float oblique_angle_degrees = 45.0f;                 // receding direction, from +X
  float oblique_scale = 0.5f;                          // 1 cavalier, 0.5 cabinet
  UpAxis up = UpAxis::pos_y;
  std::optional<int> file_camera;  // view through the model file's camera N instead (file_camera_view)
  // Zoom and centre the framed view on what the model covers of the image (fill_image), as thumbnails are framed:
  // a sphere's framing leaves a long or flat model small. Not with a file's camera, sheets or turntables.
  bool fill = false;
};

// The share of the image's tighter side that a filled view's model spans (CameraSpec::fill): a 4% margin each side.
inline constexpr float kFillExtent = 0.92f;

// Framing of a mesh's positions. Throws InputError(source, ...) when its coordinates are too large to frame.
Framing framing_of(const Mesh& mesh, const std::string& source);

// The view of a model framed by `framing`, for a target of the given aspect (width / height). Throws
// std::invalid_argument naming the field for a camera that cannot be built (the eye at the focal point, near not
// positive for a perspective, far not beyond near, a degenerate window or view up).
View make_view(const CameraSpec& camera, const Framing& framing, float aspect);

// `view` zoomed and shifted on the image so that the points' projected bounds are centred and span kFillExtent of
// the image along the tighter axis. The points must lie in front of the eye (any view from make_view frames them
// so); only the projection's x and y change, so depth and clipping are as before. At most a 1000-fold zoom, for
// a model that projects to a point or a line.
View fill_image(const View& view, std::span<const glm::vec3> world_points);

// The view through camera `index` of mesh.cameras (a glTF file's cameras, in scene order), for a target of the
// given aspect: its pose, its near and far planes (an infinite far plane ends behind the model's framing sphere),
// and its vertical field of view, or its orthographic ymag, with the width following the image's aspect.
// Throws std::invalid_argument for an index the mesh has no camera for, InputError(source, ...) for a camera
// that cannot be used (znear not positive, zfar not beyond it, yfov outside (0, pi), ymag not positive).
View file_camera_view(const Mesh& mesh, int index, const Framing& framing, float aspect, const std::string& source);

// The camera of a View in the conventions of computer-vision tools, for turning depth back into world points.
// OpenCV camera axes: x right, y down, z forward (into the scene); pixel (0, 0)'s centre is at u = v = 0.
struct CameraModel {
  bool perspective = true;         // false: a parallel projection (orthographic, oblique, the view presets)
  glm::mat3 K{1.0f};               // intrinsics in pixels (perspective only): u = fx X/Z + cx, v = fy Y/Z + cy
  glm::mat4 world_from_camera;     // OpenGL camera axes (x right, y up, looking down -z)
  glm::mat4 camera_from_world_cv;  // OpenCV camera axes
};

// The camera model of `view` for a width x height image. A parallel projection has no K; its pixel-to-point map
// is clip_from_view's inverse.
CameraModel camera_model(const View& view, int width, int height);

// JSON: width, height, near, far, projection ("perspective" or "parallel"), K (3x3, rows; null when parallel),
// world_from_camera (OpenGL axes) and camera_from_world (OpenCV axes), 4x4 row by row, and clip_from_view.
std::string camera_json(const View& view, int width, int height);

}  // namespace facet
