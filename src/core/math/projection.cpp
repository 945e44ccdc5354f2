// projection.cpp - OpenGL projection matrices and classical (axonometric, multiview) view presets.
#include "facet/projection.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "facet/transform.hpp"

namespace facet {
namespace {

void require(bool ok, const char* fn, const char* problem) {
  if (!ok) throw std::invalid_argument(std::string(fn) + ": " + problem);
}

void require_finite(float v, const char* fn, const char* name) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(fn) + ": " + name + " must be finite");
}

// Shared by frustum, ortho and oblique: all six box parameters finite, non-empty extents.
void check_box(const char* fn, float l, float r, float b, float t, float n, float f) {
  require_finite(l, fn, "left");
  require_finite(r, fn, "right");
  require_finite(b, fn, "bottom");
  require_finite(t, fn, "top");
  require_finite(n, fn, "near");
  require_finite(f, fn, "far");
  require(l != r, fn, "left must differ from right");
  require(b != t, fn, "bottom must differ from top");
  require(f > n, fn, "far must be greater than near");
}

float deg(double degrees) { return float(degrees * std::numbers::pi / 180.0); }

}  // namespace

glm::mat4 perspective(float fovy_radians, float aspect, float near, float far) {
  const char* fn = "perspective";
  require_finite(fovy_radians, fn, "fovy");
  require_finite(aspect, fn, "aspect");
  require_finite(near, fn, "near");
  require_finite(far, fn, "far");
  require(fovy_radians > 0.0f && double(fovy_radians) < std::numbers::pi, fn, "fovy must be in (0, pi) radians");
  require(aspect > 0.0f, fn, "aspect must be positive");
  require(near > 0.0f, fn, "near must be positive");
  require(far > near, fn, "far must be greater than near");
  // gluPerspective, evaluated in double so the depth terms keep their precision when far/near is large.
  const double f = 1.0 / std::tan(double(fovy_radians) / 2.0);
  const double n = near, fa = far;
  glm::mat4 m(0.0f);
  m[0][0] = float(f / aspect);
  m[1][1] = float(f);
  m[2][2] = float((fa + n) / (n - fa));
  m[2][3] = -1.0f;
  m[3][2] = float(2.0 * fa * n / (n - fa));
  return m;
}

glm::mat4 frustum(float left, float right, float bottom, float top, float near, float far) {
  const char* fn = "frustum";
  check_box(fn, left, right, bottom, top, near, far);
  require(near > 0.0f, fn, "near must be positive");
  const double l = left, r = right, b = bottom, t = top, n = near, f = far;
  glm::mat4 m(0.0f);
  m[0][0] = float(2.0 * n / (r - l));
  m[1][1] = float(2.0 * n / (t - b));
  m[2][0] = float((r + l) / (r - l));
  m[2][1] = float((t + b) / (t - b));
  m[2][2] = float(-(f + n) / (f - n));
  m[2][3] = -1.0f;
  m[3][2] = float(-2.0 * f * n / (f - n));
  return m;
}

glm::mat4 ortho(float left, float right, float bottom, float top, float near, float far) {
  check_box("ortho", left, right, bottom, top, near, far);
  const double l = left, r = right, b = bottom, t = top, n = near, f = far;
  glm::mat4 m(1.0f);
  m[0][0] = float(2.0 / (r - l));
  m[1][1] = float(2.0 / (t - b));
  m[2][2] = float(-2.0 / (f - n));
  m[3][0] = float(-(r + l) / (r - l));
  m[3][1] = float(-(t + b) / (t - b));
  m[3][2] = float(-(f + n) / (f - n));
  return m;
}

glm::mat4 oblique(float angle_radians, float depth_scale, float left, float right, float bottom, float top, float near,
                  float far, float pivot_distance) {
  const char* fn = "oblique";
  require_finite(angle_radians, fn, "angle");
  require_finite(depth_scale, fn, "depth_scale");
  require_finite(pivot_distance, fn, "pivot_distance");
  require(depth_scale >= 0.0f, fn, "depth_scale must be non-negative");
  check_box(fn, left, right, bottom, top, near, far);
  const double cot_theta = double(depth_scale) * std::cos(double(angle_radians));
  const double cot_phi = double(depth_scale) * std::sin(double(angle_radians));
  // x' = x - cot(theta) * (z + pivot): eye-space z grows towards the viewer, so points further away than the
  // pivot plane move along +(cos, sin) of the receding angle.
  glm::mat4 h(1.0f);
  h[2][0] = float(-cot_theta);
  h[2][1] = float(-cot_phi);
  h[3][0] = float(-cot_theta * pivot_distance);
  h[3][1] = float(-cot_phi * pivot_distance);
  return ortho(left, right, bottom, top, near, far) * h;
}

glm::mat4 isometric_view() {
  // asin(tan 30deg) tilts the (1,1,1) diagonal, already swung into the YZ plane by the -45deg turn, onto +Z.
  return rotate_x(float(std::asin(std::tan(std::numbers::pi / 6.0)))) * rotate_y(deg(-45.0));
}

glm::mat4 dimetric_view() { return rotate_x(deg(30.0)) * rotate_y(deg(-45.0)); }

glm::mat4 trimetric_view() { return rotate_x(deg(30.0)) * rotate_y(deg(-30.0)); }

glm::mat4 front_view() { return glm::mat4(1.0f); }

// Written out rather than rotate_x(pi/2) so the entries are exact 0/1 (cos(float(pi/2)) is -4.4e-8, not 0).
glm::mat4 top_view() {
  glm::mat4 m(1.0f);
  m[1] = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);   // world +Y -> eye +Z (towards the viewer above)
  m[2] = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);  // world +Z -> eye -Y (the front edge at the bottom)
  return m;
}

glm::mat4 side_view() {
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);   // world +X -> eye +Z (towards the viewer on the right)
  m[2] = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);  // world +Z -> eye -X (the front at the left edge)
  return m;
}

}  // namespace facet
