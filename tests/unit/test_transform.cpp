// test_transform.cpp - model transforms, look_at and the normal matrix against hand-computed and published matrices.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "facet/transform.hpp"
#include "support/matrix_asserts.hpp"

namespace facet::transform_tests {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// `expected` is given the way the WebGL tutorials write matrices: 16 numbers, column by column (OpenGL / WebGL order).
void expect_columns(const glm::mat4& m, const float (&expected)[16], float tol = 1e-5f) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c * 4 + r], tol) << "column " << c << " row " << r;
}

using test::expect_mat_near;
using test::expect_vec_near;

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

TEST(TransformTest, TranslateAndScaleAreTheTextbookMatrices) {
  expect_columns(translate({1.0f, -2.0f, 3.5f}), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, -2, 3.5f, 1});
  expect_columns(scale({2.0f, 3.0f, -4.0f}), {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, -4, 0, 0, 0, 0, 1});
  expect_columns(scale(0.5f), {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 1});
  // A direction (w = 0) ignores the translation, a point (w = 1) does not (MDN's "WebGL model view projection").
  const glm::vec4 dir = translate({5.0f, 6.0f, 7.0f}) * glm::vec4(1.0f, 2.0f, 3.0f, 0.0f);
  EXPECT_EQ(dir, glm::vec4(1.0f, 2.0f, 3.0f, 0.0f));
  expect_vec_near(apply(translate({5.0f, 6.0f, 7.0f}), {1.0f, 2.0f, 3.0f}), {6.0f, 8.0f, 10.0f});
}

TEST(TransformTest, AxisRotationsAreCounterClockwiseAboutTheirAxis) {
  const float a = glm::radians(30.0f), c = std::cos(a), s = std::sin(a);
  expect_columns(rotate_x(a), {1, 0, 0, 0, 0, c, s, 0, 0, -s, c, 0, 0, 0, 0, 1});
  expect_columns(rotate_y(a), {c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0, 0, 0, 0, 1});
  expect_columns(rotate_z(a), {c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  // Quarter turns: y -> z, z -> x, x -> y.
  expect_vec_near(apply(rotate_x(kPi / 2), {0, 1, 0}), {0, 0, 1});
  expect_vec_near(apply(rotate_y(kPi / 2), {0, 0, 1}), {1, 0, 0});
  expect_vec_near(apply(rotate_z(kPi / 2), {1, 0, 0}), {0, 1, 0});
}

TEST(TransformTest, ArbitraryAxisRotationMatchesAxisRotationsAndRodrigues) {
  for (float a : {-2.0f, -0.3f, 0.0f, 0.7f, 3.0f}) {
    expect_mat_near(rotate(a, {1, 0, 0}), rotate_x(a));
    expect_mat_near(rotate(a, {0, 2.5f, 0}), rotate_y(a));  // the axis need not be unit length
    expect_mat_near(rotate(a, {0, 0, 1e-20f}), rotate_z(a));
    expect_mat_near(rotate(a, {0, 0, -1}), rotate_z(-a));
  }
  // 120 degrees about the cube diagonal cycles the axes: x -> y -> z -> x.
  const glm::mat4 r = rotate(2.0f * kPi / 3.0f, {1, 1, 1});
  expect_vec_near(apply(r, {1, 0, 0}), {0, 1, 0});
  expect_vec_near(apply(r, {0, 1, 0}), {0, 0, 1});
  expect_vec_near(apply(r, {0, 0, 1}), {1, 0, 0});
  // Hand-computed: 90 degrees about (0, 1, 1)/sqrt2 sends x to (0, 1, -1)/sqrt2.
  const float h = std::sqrt(0.5f);
  expect_vec_near(apply(rotate(kPi / 2, {0, 1, 1}), {1, 0, 0}), {0, h, -h});
  EXPECT_NEAR(glm::determinant(rotate(1.234f, {0.3f, -0.4f, 0.8f})), 1.0f, 1e-5f);
}

// "Barebones 3D rendering with WebGL": scale by 2, rotate about Y by a, rotate about X by a, translate
// z by -9, written out column-major as
//   c*x,  s*s*x, -c*s*x, 0,   0, c*x, s*x, 0,   s*x, -c*s*x, c*c*x, 0,   0, 0, tz, 1.
TEST(TransformTest, RotatingCubeModelMatrixIsTranslateRotateXRotateYScale) {
  for (float t : {0.0f, 700.0f, 1234.5f, 3999.0f}) {
    const float a = t * kPi / 4000.0f, c = std::cos(a), s = std::sin(a), x = 2.0f, tz = -9.0f;
    const float expected[16] = {c * x, s * s * x,  -c * s * x, 0, 0, c * x, s * x, 0,
                                s * x, -c * s * x, c * c * x,  0, 0, 0,     tz,    1};
    expect_columns(translate({0, 0, tz}) * rotate_x(a) * rotate_y(a) * scale(x), expected);
  }
}

// The CIS367 lecture notes "Building models / Viewing", "Moving the camera": model-view =
// mult(translate(0, 0, -d), rotateY(90)) shows the side of the object: the camera sits on -X at distance d looking
// at the origin.
TEST(TransformTest, LectureSideViewIsTranslateAfterRotateY) {
  const float d = 4.0f;
  expect_mat_near(translate({0, 0, -d}) * rotate_y(kPi / 2), look_at({-d, 0, 0}, {0, 0, 0}, {0, 1, 0}));
}

// The camera frame: columns right, up, back (= -forward) and the eye. look_at must be its inverse.
glm::mat4 camera_frame(glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
  const glm::vec3 back = glm::normalize(eye - target);
  const glm::vec3 right = glm::normalize(glm::cross(up, back));
  const glm::vec3 true_up = glm::cross(back, right);
  return glm::mat4(glm::vec4(right, 0), glm::vec4(true_up, 0), glm::vec4(back, 0), glm::vec4(eye, 1));
}

TEST(TransformTest, LookAtIsTheInverseOfTheCameraFrame) {
  struct Case {
    glm::vec3 eye, target, up;
  };
  const Case cases[] = {{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}},      {{1, 1, 1}, {0, 0, 0}, {0, 1, 0}},
                        {{3, -2, 7}, {-1, 4, 0.5f}, {0, 0, 1}}, {{-5, 2, -3}, {1, 1, 1}, {0.3f, 1, -0.2f}},
                        {{10, 0, 0}, {0, 0, 0}, {0, 1, 0}},     {{0.1f, 8, 0}, {0, 0, 0}, {0, 0, -1}}};
  for (const Case& k : cases) {
    const glm::mat4 view = look_at(k.eye, k.target, k.up);
    expect_mat_near(view, glm::inverse(camera_frame(k.eye, k.target, k.up)), 1e-4f);
    // The eye goes to the origin, the target straight ahead down -Z at its distance.
    expect_vec_near(apply(view, k.eye), {0, 0, 0}, 1e-4f);
    expect_vec_near(apply(view, k.target), {0, 0, -glm::length(k.target - k.eye)}, 1e-4f);
    // `up` lands in the upper half of the screen, on the y axis' side.
    EXPECT_GT(glm::vec3(view * glm::vec4(k.up, 0)).y, 0.0f);
  }
  // Hand-computed: the default camera moved back 5 is a pure translation.
  expect_columns(look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -5, 1});
  // Looking down +X from the origin: world +X is straight ahead (-Z), world +Z is screen right.
  expect_columns(look_at({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1});
}

TEST(TransformTest, LookAtRejectsDegenerateInput) {
  EXPECT_THROW(look_at({1, 2, 3}, {1, 2, 3}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(look_at({0, 0, 0}, {0, 5, 0}, {0, 1, 0}), std::invalid_argument);  // up along the view
  EXPECT_THROW(look_at({0, 5, 0}, {0, 0, 0}, {0, 2, 0}), std::invalid_argument);  // up opposite the view
  EXPECT_THROW(look_at({0, 0, 5}, {0, 0, 0}, {0, 0, 0}), std::invalid_argument);  // no up at all
  EXPECT_THROW(look_at({kNaN, 0, 5}, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(look_at({0, 0, 5}, {0, kInf, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(look_at({0, 0, 5}, {0, 0, 0}, {0, kNaN, 0}), std::invalid_argument);
  EXPECT_NO_THROW(look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 1e-3f}));  // tilted up is fine
}

TEST(TransformTest, NormalMatrixIsTheInverseTransposeOfTheUpper3x3) {
  const glm::mat3 n = normal_matrix(translate({4, 5, 6}) * scale({2, 4, 0.5f}));
  const glm::mat3 expected(glm::vec3(0.5f, 0, 0), glm::vec3(0, 0.25f, 0), glm::vec3(0, 0, 2));
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(n[c][r], expected[c][r], 1e-6f);
  // For a rotation the normal matrix is the rotation itself.
  const glm::mat4 rot = rotate(0.8f, {1, 2, 3});
  const glm::mat3 nr = normal_matrix(rot);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(nr[c][r], rot[c][r], 1e-5f);
  // Under non-uniform scale the transformed normal stays perpendicular to transformed tangents, while the plain
  // upper 3x3 would tilt it.
  const glm::mat4 m = rotate_z(0.4f) * scale({3, 1, 0.2f}) * rotate_x(0.9f);
  const glm::vec3 normal = glm::normalize(glm::vec3(1, 1, 1));
  const glm::vec3 t1(1, -1, 0), t2(0, 1, -1);  // both perpendicular to the normal
  const glm::vec3 nn = normal_matrix(m) * normal;
  const glm::mat3 m3(m);
  EXPECT_NEAR(glm::dot(nn, m3 * t1), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(nn, m3 * t2), 0.0f, 1e-5f);
  EXPECT_GT(std::abs(glm::dot(m3 * normal, m3 * t1)), 0.1f);
  // Scale-invariant singularity test: tiny uniform scale is fine, flattening is not.
  EXPECT_NO_THROW(normal_matrix(scale(1e-4f)));
  EXPECT_THROW(normal_matrix(scale({1, 0, 1})), std::invalid_argument);
  glm::mat4 bad(1.0f);
  bad[1][2] = kNaN;
  EXPECT_THROW(normal_matrix(bad), std::invalid_argument);
}

TEST(TransformTest, TransformsRejectNonFiniteInput) {
  EXPECT_THROW(translate({kNaN, 0, 0}), std::invalid_argument);
  EXPECT_THROW(scale({1, kInf, 1}), std::invalid_argument);
  EXPECT_THROW(scale(kNaN), std::invalid_argument);
  EXPECT_THROW(rotate(kNaN, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(rotate(1.0f, {0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(rotate(1.0f, {kInf, 0, 0}), std::invalid_argument);
  EXPECT_THROW(rotate_x(kInf), std::invalid_argument);
  EXPECT_THROW(rotate_y(kNaN), std::invalid_argument);
  EXPECT_THROW(rotate_z(-kInf), std::invalid_argument);
  try {
    rotate(1.0f, {0, 0, 0});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rotate: axis"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facet::transform_tests
