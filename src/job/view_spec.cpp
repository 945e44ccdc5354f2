// view_spec.cpp - a CameraSpec and a model's framing turned into a View: presets, framing, the projections.
#include "facet/view_spec.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "facet/camera.hpp"
#include "facet/error.hpp"
#include "facet/projection.hpp"
#include "facet/splats.hpp"

namespace facet {
namespace {

std::string format(float v, const char* spec = "%g") {
  char text[32];
  std::snprintf(text, sizeof text, spec, static_cast<double>(v));
  return text;
}

// Half extents (x, y) grown to the target's aspect, with the same 8% margin frame_sphere keeps.
std::array<float, 4> fit_extents(float half_x, float half_y, float aspect) {
  const float half_h = 1.08f * std::max(half_y, half_x / aspect);
  const float half_w = half_h * aspect;
  return {-half_w, half_w, -half_h, half_h};
}

// The classical views, in Projection order from isometric on; oblique projects onto the front plane.
bool is_preset(Projection kind) { return kind >= Projection::isometric; }
glm::mat4 preset_rotation(Projection kind) {
  if (!is_preset(kind)) return front_view();
  using Rotation = glm::mat4 (*)();
  constexpr Rotation views[] = {isometric_view, dimetric_view, trimetric_view, front_view, top_view, side_view};
  return views[static_cast<int>(kind) - static_cast<int>(Projection::isometric)]();
}

// Where the camera is and what it looks at, before the projection: framed on the sphere around the focal point
// that still holds the whole model, or placed where the spec puts it with near and far hugging the model.
Camera place_camera(const CameraSpec& spec, const Framing& framing, float aspect, float& reach) {
  const glm::mat3 world_from_upright = glm::transpose(upright_from_model(spec.up));
  const bool preset = is_preset(spec.projection);
  glm::vec3 direction, up;
  if (preset || spec.projection == Projection::oblique) {
    // Classical views look along the preset's axis; oblique projects onto the front plane.
    const glm::mat3 upright_from_eye = glm::transpose(glm::mat3(preset_rotation(spec.projection)));
    direction = world_from_upright * upright_from_eye * glm::vec3(0, 0, 1);
    up = world_from_upright * upright_from_eye * glm::vec3(0, 1, 0);
  } else {
    // A 3/4 view: from +Z turned 30 degrees towards +X and lifted 20 degrees.
    const float az = glm::radians(30.0f), el = glm::radians(20.0f);
    direction = world_from_upright * glm::vec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    up = world_from_upright * glm::vec3(0, 1, 0);
  }
  if (spec.view_up) up = *spec.view_up;
  const glm::vec3 focal = spec.focal_point.value_or(framing.center);
  reach = framing.radius + glm::distance(focal, framing.center);
  if (!(reach > 0.0f)) reach = 1.0f;
  const bool orthographic = spec.projection != Projection::perspective && spec.projection != Projection::frustum;

  Camera camera;
  camera.view_angle_degrees = spec.view_angle_degrees;
  if (spec.position && !preset) {
    if (*spec.position == focal) throw std::invalid_argument("camera position: must differ from the focal point");
    camera.position = *spec.position;
    camera.focal_point = focal;
    camera.view_up = up;
    const glm::vec3 forward = glm::normalize(focal - camera.position);
    const float depth = glm::dot(framing.center - camera.position, forward);
    const float r = std::max(framing.radius, 1e-6f);
    camera.far = std::max(depth + 1.05f * r, 1e-3f);
    camera.near = orthographic ? depth - 1.05f * r : std::max(depth - 1.05f * r, 1e-3f * (std::abs(depth) + r));
    if (!(camera.far > camera.near)) camera.far = camera.near + 2.1f * r;
  } else {
    camera = frame_sphere(focal, reach, aspect, spec.view_angle_degrees, direction, up);
  }
  if (spec.azimuth_degrees != 0.0f || spec.elevation_degrees != 0.0f)
    apply_azimuth_elevation(camera, spec.azimuth_degrees, spec.elevation_degrees);
  if (spec.near) camera.near = *spec.near;
  if (spec.far) camera.far = *spec.far;
  if (!orthographic && !(camera.near > 0.0f))
    throw std::invalid_argument("near: must be positive for a perspective projection, got " + format(camera.near));
  if (!(camera.far > camera.near))
    throw std::invalid_argument("far: must be greater than the near distance (near " + format(camera.near) + ", far " +
                                format(camera.far) + ")");
  return camera;
}

}  // namespace

std::optional<UpAxis> parse_up_axis(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (text.size() == 1) return parse_up_axis(std::string("+") + text.front());
  if (text.size() != 2 || (text[0] != '+' && text[0] != '-')) return std::nullopt;
  const bool positive = text[0] == '+';
  switch (std::toupper(static_cast<unsigned char>(text[1]))) {
    case 'X': return positive ? UpAxis::pos_x : UpAxis::neg_x;
    case 'Y': return positive ? UpAxis::pos_y : UpAxis::neg_y;
    case 'Z': return positive ? UpAxis::pos_z : UpAxis::neg_z;
    default: return std::nullopt;
  }
}

glm::mat3 upright_from_model(UpAxis up) {
  // Exact columns (images of +X, +Y, +Z) rather than rotate_*() so no rounding creeps into the axes.
  const auto columns = [](glm::vec3 x, glm::vec3 y, glm::vec3 z) { return glm::mat3(x, y, z); };
  switch (up) {
    case UpAxis::pos_y: break;
    case UpAxis::neg_y: return columns({-1, 0, 0}, {0, -1, 0}, {0, 0, 1});
    case UpAxis::pos_z: return columns({1, 0, 0}, {0, 0, -1}, {0, 1, 0});
    case UpAxis::neg_z: return columns({1, 0, 0}, {0, 0, 1}, {0, -1, 0});
    case UpAxis::pos_x: return columns({0, 1, 0}, {-1, 0, 0}, {0, 0, 1});
    case UpAxis::neg_x: return columns({0, -1, 0}, {1, 0, 0}, {0, 0, 1});
  }
  return glm::mat3(1.0f);
}

Framing framing_of(const Mesh& mesh, const std::string& source) {
  Framing framing;
  framing.center = bounds(mesh).center();
  // The sphere about the box centre through the farthest vertex: at most the box's half diagonal, and often much
  // tighter, so the model fills more of the frame.
  for (const glm::vec3& p : mesh.positions) framing.radius = std::max(framing.radius, glm::distance(p, framing.center));
  // Gaussian splats reach three standard deviations past their centres, as far as the rasterizer draws them.
  if (mesh.splats)
    for (std::size_t i = 0; i < mesh.splats->size(); ++i) {
      const glm::vec3 s = mesh.splats->scales[i];
      const float reach = 3.0f * std::max(s.x, std::max(s.y, s.z));
      framing.radius = std::max(framing.radius, glm::distance(mesh.splats->positions[i], framing.center) + reach);
    }
  // Coordinates near the float limit overflow the camera distance; such a model cannot be framed.
  if (!std::isfinite(framing.radius) || !std::isfinite(glm::length(framing.center)) || framing.radius > 1e30f)
    throw InputError(source, "coordinates too large to frame (bounding radius " + format(framing.radius) + ")");
  // A camera a few radii from the centre must differ from it in float: a model whose size (1 where it is a point) is
  // under 1e-6 of its distance from the origin (a few float steps) cannot be seen from nearby.
  const glm::vec3 far_out = glm::abs(framing.center);
  const float distance = std::max(far_out.x, std::max(far_out.y, far_out.z));
  if ((framing.radius > 0.0f ? framing.radius : 1.0f) < 1e-6f * distance)
    throw InputError(source, "the model is too small for its distance from the origin to be framed (bounding radius " +
                                 format(framing.radius) + " at " + format(distance) + ")");
  return framing;
}

View make_view(const CameraSpec& spec, const Framing& framing, float aspect) {
  float reach = 0.0f;
  const Camera camera = place_camera(spec, framing, aspect, reach);
  View view;
  view.view_from_world = view_from_world(camera);
  view.near = camera.near;
  view.far = camera.far;
  switch (spec.projection) {
    case Projection::perspective: view.clip_from_view = clip_from_view(camera, aspect); break;
    case Projection::frustum: {
      const float t = camera.near * std::tan(glm::radians(camera.view_angle_degrees) * 0.5f);
      const std::array<float, 4> w = spec.frustum_window.value_or(std::array<float, 4>{-t * aspect, t * aspect, -t, t});
      view.clip_from_view = frustum(w[0], w[1], w[2], w[3], camera.near, camera.far);
      break;
    }
    case Projection::oblique: {
      const float a = glm::radians(spec.oblique_angle_degrees), s = spec.oblique_scale;
      // The shear turns the model's sphere into an ellipsoid reaching r * sqrt(1 + k^2) along each screen axis.
      const std::array<float, 4> w = spec.ortho_window.value_or(
          fit_extents(reach * std::hypot(1.0f, s * std::cos(a)), reach * std::hypot(1.0f, s * std::sin(a)), aspect));
      const float pivot = glm::distance(camera.position, camera.focal_point);
      view.clip_from_view = oblique(a, s, w[0], w[1], w[2], w[3], camera.near, camera.far, pivot);
      break;
    }
    default: {
      const std::array<float, 4> w = spec.ortho_window.value_or(fit_extents(reach, reach, aspect));
      view.clip_from_view = ortho(w[0], w[1], w[2], w[3], camera.near, camera.far);
      break;
    }
  }
  return view;
}

View fill_image(const View& view, std::span<const glm::vec3> world_points) {
  const glm::mat4 clip_from_world = view.clip_from_view * view.view_from_world;
  glm::vec2 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
  for (const glm::vec3& p : world_points) {
    const glm::vec4 clip = clip_from_world * glm::vec4(p, 1.0f);
    if (!(clip.w > 0.0f)) continue;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    low = glm::min(low, ndc);
    high = glm::max(high, ndc);
  }
  if (!(low.x <= high.x && low.y <= high.y)) return view;
  const glm::vec2 extent = high - low, centre = 0.5f * (low + high);
  // NDC spans 2 along each axis whatever the aspect: the tighter axis sets one zoom for both.
  constexpr float kMostZoom = 1000.0f;
  const float zoom = std::min({2.0f * kFillExtent / std::max(extent.x, 1e-30f),
                               2.0f * kFillExtent / std::max(extent.y, 1e-30f), kMostZoom});
  // ndc' = zoom (ndc - centre), applied in clip space: x' = zoom x - zoom centre.x w, and so for y.
  glm::mat4 ndc_fill(1.0f);
  ndc_fill[0][0] = ndc_fill[1][1] = zoom;
  ndc_fill[3][0] = -zoom * centre.x;
  ndc_fill[3][1] = -zoom * centre.y;
  View filled = view;
  filled.clip_from_view = ndc_fill * view.clip_from_view;
  return filled;
}

View file_camera_view(const Mesh& mesh, int index, const Framing& framing, float aspect, const std::string& source) {
  if (index < 0 || static_cast<std::size_t>(index) >= mesh.cameras.size())
    throw std::invalid_argument("camera index " + std::to_string(index) + ": the model has " +
                                std::to_string(mesh.cameras.size()) + " camera(s)");
  const ModelCamera& camera = mesh.cameras[static_cast<std::size_t>(index)];
  const std::string which = "camera " + std::to_string(index);
  const auto fail = [&](const std::string& problem) -> void { throw InputError(source, which + ": " + problem); };
  if (!(camera.znear > 0.0f) || !std::isfinite(camera.znear)) fail("znear must be positive");
  if (camera.zfar && !(*camera.zfar > camera.znear && std::isfinite(*camera.zfar)))
    fail("zfar must be greater than znear");
  View view;
  view.view_from_world = glm::inverse(camera.world_from_camera);
  const float det = glm::determinant(glm::mat3(camera.world_from_camera));
  if (!(std::abs(det) > 0.5f) || !std::isfinite(glm::length(view.view_from_world[3])))
    fail("its node's transform is singular or not finite");
  view.near = camera.znear;
  if (camera.zfar) {
    view.far = *camera.zfar;
  } else {
    // An infinite far plane: the model's far side bounds what is drawn, so the depth range stops there.
    const glm::vec3 center(view.view_from_world * glm::vec4(framing.center, 1.0f));
    view.far = std::max(-center.z + 1.05f * framing.radius, 2.0f * view.near);
  }
  // The file's aspect ratio is the one it was framed for; the image's own keeps pixels square, as glTF viewers do.
  if (camera.perspective) {
    if (!(camera.yfov_radians > 0.0f && camera.yfov_radians < 3.14159f)) fail("yfov must lie between 0 and pi");
    view.clip_from_view = perspective(camera.yfov_radians, aspect, view.near, view.far);
  } else {
    const float half_h = camera.magnification.y, half_w = half_h * aspect;
    if (!(half_h > 0.0f) || !std::isfinite(half_w)) fail("ymag must be positive");
    view.clip_from_view = ortho(-half_w, half_w, -half_h, half_h, view.near, view.far);
  }
  return view;
}

CameraModel camera_model(const View& view, int width, int height) {
  CameraModel model;
  const glm::mat4& p = view.clip_from_view;
  // A perspective divides by -z: its last row is (0, 0, -1, 0).
  model.perspective = p[0][3] == 0.0f && p[1][3] == 0.0f && p[2][3] == -1.0f && p[3][3] == 0.0f;
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  if (model.perspective) {
    // x_ndc = p00 X/Z - p20 with X = x, Z = -z; pixel centres sit half a pixel in from the corner at 0.
    model.K = glm::mat3(1.0f);
    model.K[0][0] = p[0][0] * w * 0.5f;
    model.K[1][1] = p[1][1] * h * 0.5f;
    model.K[2][0] = (1.0f - p[2][0]) * w * 0.5f - 0.5f;
    model.K[2][1] = (1.0f + p[2][1]) * h * 0.5f - 0.5f;
  }
  model.world_from_camera = glm::inverse(view.view_from_world);
  const glm::mat4 cv_from_gl = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, -1.0f, -1.0f));
  model.camera_from_world_cv = cv_from_gl * view.view_from_world;
  return model;
}

std::string camera_json(const View& view, int width, int height) {
  const CameraModel model = camera_model(view, width, height);
  std::string out;
  // Nine significant digits: enough for every float to read back exactly.
  const auto number = [&](float v) { out += format(v, "%.9g"); };
  const auto rows = [&](auto m, int n) {
    out += '[';
    for (int r = 0; r < n; ++r) {
      out += r ? ", [" : "[";
      for (int c = 0; c < n; ++c) {
        if (c) out += ", ";
        number(m[c][r]);
      }
      out += ']';
    }
    out += ']';
  };
  out += "{\n  \"width\": " + std::to_string(width) + ",\n  \"height\": " + std::to_string(height) + ",\n  \"near\": ";
  number(view.near);
  out += ",\n  \"far\": ";
  number(view.far);
  out += std::string(",\n  \"projection\": \"") + (model.perspective ? "perspective" : "parallel") + "\",\n  \"K\": ";
  if (model.perspective) rows(model.K, 3);
  else out += "null";
  out += ",\n  \"world_from_camera\": ";
  rows(model.world_from_camera, 4);
  out += ",\n  \"camera_from_world\": ";
  rows(model.camera_from_world_cv, 4);
  out += ",\n  \"clip_from_view\": ";
  rows(view.clip_from_view, 4);
  out += "\n}\n";
  return out;
}

}  // namespace facet
