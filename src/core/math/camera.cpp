// camera.cpp - VTK-style camera helpers, sphere framing and azimuth/elevation rotations.
#include "facet/camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "facet/projection.hpp"
#include "facet/transform.hpp"

namespace facet {
namespace {

// Same threshold as look_at, so anything accepted here is also accepted there.
constexpr double kParallel = 1e-6;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void require(bool ok, const char* fn, const char* problem) {
  if (!ok) throw std::invalid_argument(std::string(fn) + ": " + problem);
}

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Rodrigues rotation of v about the unit axis k.
glm::dvec3 rotate_about(glm::dvec3 v, glm::dvec3 k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0 - c));
}

// Unit right vector of a camera looking along unit `dir` with `up`, or a throw when up is zero or parallel.
glm::dvec3 right_axis(glm::dvec3 dir, glm::dvec3 up, const char* fn) {
  const double up_len = glm::length(up);
  require(up_len > 0.0, fn, "view up must be non-zero");
  const glm::dvec3 r = glm::cross(dir, up / up_len);
  const double len = glm::length(r);
  require(len >= kParallel, fn, "view up must not be parallel to the view direction");
  return r / len;
}

}  // namespace

glm::mat4 view_from_world(const Camera& camera) { return look_at(camera.position, camera.focal_point, camera.view_up); }

glm::mat4 clip_from_view(const Camera& camera, float aspect) {
  require(std::isfinite(camera.view_angle_degrees), "clip_from_view", "view angle must be finite");
  return perspective(float(radians(camera.view_angle_degrees)), aspect, camera.near, camera.far);
}

Camera frame_sphere(glm::vec3 center, float radius, float aspect, float view_angle_degrees, glm::vec3 direction,
                    glm::vec3 up) {
  const char* fn = "frame_sphere";
  require(finite(center) && finite(direction) && finite(up), fn, "center, direction and up must be finite");
  require(std::isfinite(radius) && radius > 0.0f, fn, "radius must be positive and finite");
  require(std::isfinite(aspect) && aspect > 0.0f, fn, "aspect must be positive and finite");
  require(std::isfinite(view_angle_degrees) && view_angle_degrees > 0.0f && view_angle_degrees < 180.0f, fn,
          "view angle must be in (0, 180) degrees");
  const double dir_len = glm::length(glm::dvec3(direction));
  require(dir_len > 0.0, fn, "direction must be non-zero");
  const glm::dvec3 to_eye = glm::dvec3(direction) / dir_len;
  const glm::dvec3 right = right_axis(-to_eye, glm::dvec3(up), fn);
  const glm::dvec3 true_up = glm::cross(right, -to_eye);

  // NDC is linear in the tangent of the angle off-axis, so shrinking the tangent of the tighter half-angle by
  // the margin puts the sphere's silhouette at exactly 1 / kMargin of that NDC half-extent.
  constexpr double kMargin = 1.08;
  const double tan_v = std::tan(radians(view_angle_degrees) / 2.0);
  const double tan_half = std::min(tan_v, tan_v * double(aspect));
  const double silhouette = std::atan(tan_half / kMargin);  // angular radius the sphere may subtend
  const double dist = double(radius) / std::sin(silhouette);

  Camera camera;
  camera.focal_point = center;
  camera.position = glm::vec3(glm::dvec3(center) + to_eye * dist);
  camera.view_up = glm::vec3(true_up);
  camera.view_angle_degrees = view_angle_degrees;
  camera.near = float(std::max(dist - double(radius) * 1.05, dist * 1e-3));
  camera.far = float(dist + double(radius) * 1.05);
  return camera;
}

void apply_azimuth_elevation(Camera& camera, float azimuth_deg, float elevation_deg) {
  const char* fn = "apply_azimuth_elevation";
  require(std::isfinite(azimuth_deg) && std::isfinite(elevation_deg), fn, "angles must be finite");
  require(finite(camera.position) && finite(camera.focal_point) && finite(camera.view_up), fn, "camera must be finite");
  const glm::dvec3 fp(camera.focal_point);
  glm::dvec3 offset = glm::dvec3(camera.position) - fp;
  require(glm::length(offset) > 0.0, fn, "position and focal point must differ");
  glm::dvec3 up(camera.view_up);
  require(glm::length(up) > 0.0, fn, "view up must be non-zero");

  // Azimuth: about view_up as given (VTK does not require it to be perpendicular to the view direction).
  offset = rotate_about(offset, glm::normalize(up), radians(azimuth_deg));

  // Elevation: about -right, VTK's axis (minus the first row of the view matrix), so positive angles raise the
  // camera. view_up turns with it, then is re-orthogonalised as f3d's OrthogonalizeViewUp does.
  const glm::dvec3 right = right_axis(glm::normalize(-offset), up, fn);
  const double el = radians(elevation_deg);
  offset = rotate_about(offset, -right, el);
  up = rotate_about(up, -right, el);
  const glm::dvec3 dir = glm::normalize(-offset);
  up = glm::normalize(up - dir * glm::dot(up, dir));

  camera.position = glm::vec3(fp + offset);
  camera.view_up = glm::vec3(up);
}

}  // namespace facet
