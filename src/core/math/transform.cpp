// transform.cpp - model transforms, gluLookAt and the normal matrix, with input validation.
#include "facet/transform.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace facet {
namespace {

void require_finite(float v, const char* what, const char* fn) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(fn) + ": " + what + " must be finite");
}

void require_finite(glm::vec3 v, const char* what, const char* fn) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::invalid_argument(std::string(fn) + ": " + what + " must be finite");
}

// The axis rotations are written out rather than routed through rotate() so their zero entries are exactly zero.
// Each turns the plane of axes (i, j) so that axis i moves towards axis j: (i, j) = (1, 2) about x, (2, 0) about y
// and (0, 1) about z, all counter-clockwise seen from the positive axis.
glm::mat4 plane_rotation(float radians, int i, int j, const char* fn) {
  require_finite(radians, "angle", fn);
  const float c = std::cos(radians), s = std::sin(radians);
  glm::mat4 m(1.0f);
  m[i][i] = c;
  m[i][j] = s;
  m[j][i] = -s;
  m[j][j] = c;
  return m;
}

}  // namespace

glm::mat4 translate(glm::vec3 offset) {
  require_finite(offset, "offset", "translate");
  glm::mat4 m(1.0f);
  m[3] = glm::vec4(offset, 1.0f);
  return m;
}

glm::mat4 scale(glm::vec3 factors) {
  require_finite(factors, "factors", "scale");
  glm::mat4 m(1.0f);
  m[0][0] = factors.x;
  m[1][1] = factors.y;
  m[2][2] = factors.z;
  return m;
}

glm::mat4 scale(float factor) {
  require_finite(factor, "factor", "scale");
  return scale(glm::vec3(factor));
}

glm::mat4 rotate(float radians, glm::vec3 axis) {
  require_finite(radians, "angle", "rotate");
  require_finite(axis, "axis", "rotate");
  // Normalise in double so tiny or huge (but finite) axes neither underflow nor overflow the length.
  const glm::dvec3 a(axis);
  const double len = glm::length(a);
  if (!(len > 0.0) || !std::isfinite(len)) throw std::invalid_argument("rotate: axis must be non-zero");
  const glm::dvec3 n = a / len;
  const double c = std::cos(double(radians)), s = std::sin(double(radians)), t = 1.0 - c;
  // Rodrigues: R = c*I + (1-c)*n*n^T + s*[n]x, stored column by column.
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(float(c + t * n.x * n.x), float(t * n.x * n.y + s * n.z), float(t * n.x * n.z - s * n.y), 0.0f);
  m[1] = glm::vec4(float(t * n.x * n.y - s * n.z), float(c + t * n.y * n.y), float(t * n.y * n.z + s * n.x), 0.0f);
  m[2] = glm::vec4(float(t * n.x * n.z + s * n.y), float(t * n.y * n.z - s * n.x), float(c + t * n.z * n.z), 0.0f);
  return m;
}

glm::mat4 rotate_x(float radians) { return plane_rotation(radians, 1, 2, "rotate_x"); }
glm::mat4 rotate_y(float radians) { return plane_rotation(radians, 2, 0, "rotate_y"); }
glm::mat4 rotate_z(float radians) { return plane_rotation(radians, 0, 1, "rotate_z"); }

glm::mat4 look_at(glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
  require_finite(eye, "eye", "look_at");
  require_finite(target, "target", "look_at");
  require_finite(up, "up", "look_at");
  // Double precision: the difference of two floats is exact, so "eye == target" is tested exactly, and the
  // parallel test below is not swamped by float rounding of the cross product.
  const glm::dvec3 d = glm::dvec3(target) - glm::dvec3(eye);
  const double dist = glm::length(d);
  if (!(dist > 0.0)) throw std::invalid_argument("look_at: eye and target must differ");
  const double up_len = glm::length(glm::dvec3(up));
  if (!(up_len > 0.0)) throw std::invalid_argument("look_at: up must be non-zero");
  const glm::dvec3 f = d / dist;
  const glm::dvec3 side = glm::cross(f, glm::dvec3(up) / up_len);
  const double side_len = glm::length(side);
  if (side_len < 1e-6) throw std::invalid_argument("look_at: up must not be parallel to the view direction");
  const glm::dvec3 s = side / side_len;
  const glm::dvec3 u = glm::cross(s, f);
  const glm::dvec3 e(eye);
  // Rows are the camera axes (right, up, back): the inverse of the orthonormal camera frame.
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(float(s.x), float(u.x), float(-f.x), 0.0f);
  m[1] = glm::vec4(float(s.y), float(u.y), float(-f.y), 0.0f);
  m[2] = glm::vec4(float(s.z), float(u.z), float(-f.z), 0.0f);
  m[3] = glm::vec4(float(-glm::dot(s, e)), float(-glm::dot(u, e)), float(glm::dot(f, e)), 1.0f);
  return m;
}

glm::mat3 normal_matrix(const glm::mat4& m) {
  const glm::dmat3 a{glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(a[c][r])) throw std::invalid_argument("normal_matrix: matrix must be finite");
  // Compare the determinant against Hadamard's bound (product of column lengths) so the test is scale-invariant:
  // scale(1e-3) is fine, a matrix that flattens one direction is not.
  const double det = glm::determinant(a);
  const double bound = glm::length(a[0]) * glm::length(a[1]) * glm::length(a[2]);
  if (!(std::abs(det) > 1e-12 * bound)) throw std::invalid_argument("normal_matrix: upper 3x3 is singular");
  return glm::mat3(glm::transpose(glm::inverse(a)));
}

}  // namespace facet
