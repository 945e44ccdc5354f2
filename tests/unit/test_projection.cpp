// test_projection.cpp - projections against the matrices the tutorials write out, NDC mapping, oblique and presets.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "facet/projection.hpp"
#include "facet/transform.hpp"
#include "support/matrix_asserts.hpp"

namespace facet::projection_tests {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// 16 numbers column by column: how the WebGL tutorials write matrices (as Float32Arrays).
glm::mat4 from_columns(const float (&v)[16]) {
  glm::mat4 m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = v[c * 4 + r];
  return m;
}

// 16 numbers row by row: how the CIS367 lecture slides write matrices in mathematical notation.
glm::mat4 from_rows(const float (&v)[16]) {
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = v[r * 4 + c];
  return m;
}

using test::expect_mat_near;
using test::expect_vec_near;

glm::vec3 ndc(const glm::mat4& clip_from_eye, glm::vec3 eye_point) {
  const glm::vec4 c = clip_from_eye * glm::vec4(eye_point, 1.0f);
  return glm::vec3(c) / c.w;
}

// "Barebones 3D rendering with WebGL", copied from its JavaScript:
//   f = 100; n = 0.1; t = n * tan(PI / 8); b = -t; r = t * width / height; l = -r;
//   [2n/(r-l), 0, 0, 0,  0, 2n/(t-b), 0, 0,  (r+l)/(r-l), (t+b)/(t-b), -(f+n)/(f-n), -1,  0, 0, -2fn/(f-n), 0]
TEST(ProjectionTest, BarebonesWebglFrustumStylePerspective) {
  for (float aspect : {200.0f / 200.0f, 640.0f / 480.0f, 300.0f / 700.0f}) {
    const float f = 100, n = 0.1f, t = n * std::tan(kPi / 8), b = -t, r = t * aspect, l = -r;
    const glm::mat4 expected = from_columns({2 * n / (r - l), 0, 0, 0,                                      //
                                             0, 2 * n / (t - b), 0, 0,                                      //
                                             (r + l) / (r - l), (t + b) / (t - b), -(f + n) / (f - n), -1,  //
                                             0, 0, -2 * f * n / (f - n), 0});
    expect_mat_near(frustum(l, r, b, t, n, f), expected);
    // t = n tan(pi/8) is a 45 degree vertical field of view.
    expect_mat_near(perspective(kPi / 4, aspect, n, f), expected);
  }
  // The demo's 200x200 canvas, worked out by hand: 1/tan(22.5deg) = 1 + sqrt2, -100.1/99.9, -20/99.9.
  const glm::mat4 p = perspective(kPi / 4, 1.0f, 0.1f, 100.0f);
  expect_mat_near(p, from_columns({2.41421356f, 0, 0, 0, 0, 2.41421356f, 0, 0, 0, 0, -1.00200200f, -1,  //
                                   0, 0, -0.20020020f, 0}));
}

// MDN's "WebGL model view projection": MDN.perspectiveMatrix copied from its JavaScript:
//   f = 1 / tan(fov / 2); rangeInv = 1 / (near - far);
//   [f/aspect, 0, 0, 0,  0, f, 0, 0,  0, 0, (near+far)*rangeInv, -1,  0, 0, near*far*rangeInv*2, 0]
glm::mat4 mdn_perspective(float fov, float aspect, float near, float far) {
  const float f = 1.0f / std::tan(fov / 2), range_inv = 1 / (near - far);
  return from_columns({f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (near + far) * range_inv, -1,  //
                       0, 0, near * far * range_inv * 2, 0});
}

// The same article names MDN.orthographicMatrix(left, right, bottom, top, near, far) as the drop-in replacement in
// the same demo without printing it; this is its body from the MDN shared code (the same as gl-matrix's mat4.ortho):
//   lr = 1/(left-right); bt = 1/(bottom-top); nf = 1/(near-far);
//   [-2lr, 0, 0, 0,  0, -2bt, 0, 0,  0, 0, 2nf, 0,  (left+right)lr, (top+bottom)bt, (far+near)nf, 1]
glm::mat4 mdn_orthographic(float left, float right, float bottom, float top, float near, float far) {
  const float lr = 1 / (left - right), bt = 1 / (bottom - top), nf = 1 / (near - far);
  return from_columns({-2 * lr, 0, 0, 0, 0, -2 * bt, 0, 0, 0, 0, 2 * nf, 0,  //
                       (left + right) * lr, (top + bottom) * bt, (far + near) * nf, 1});
}

TEST(ProjectionTest, MdnPerspectiveAndOrthographic) {
  // The demo's computePerspectiveMatrix: fov PI * 0.5, window aspect, near 1, far 50.
  for (float aspect : {1.0f, 1280.0f / 720.0f, 0.5f})
    expect_mat_near(perspective(kPi * 0.5f, aspect, 1.0f, 50.0f), mdn_perspective(kPi * 0.5f, aspect, 1.0f, 50.0f));
  expect_mat_near(perspective(0.7f, 1.3f, 0.25f, 300.0f), mdn_perspective(0.7f, 1.3f, 0.25f, 300.0f), 1e-4f);
  // Worked out by hand for a 1280x720 window: f = 1, f/aspect = 0.5625, 51/-49, 100/-49.
  expect_mat_near(perspective(kPi * 0.5f, 1280.0f / 720.0f, 1.0f, 50.0f),
                  from_columns({0.5625f, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1.04081633f, -1, 0, 0, -2.04081633f, 0}));
  // "near: anything at this distance will be at -1 in clip space ... far: at 1".
  const glm::mat4 p = perspective(kPi * 0.5f, 1.5f, 1.0f, 50.0f);
  EXPECT_NEAR(ndc(p, {0, 0, -1}).z, -1.0f, 1e-6f);
  EXPECT_NEAR(ndc(p, {0, 0, -50}).z, 1.0f, 1e-5f);
  // "it flips the z axis": clip w is -z_eye.
  EXPECT_FLOAT_EQ((p * glm::vec4(0.3f, 0.2f, -7.0f, 1.0f)).w, 7.0f);

  expect_mat_near(ortho(-3, 3, -2, 2, 0.5f, 40), mdn_orthographic(-3, 3, -2, 2, 0.5f, 40));
  expect_mat_near(ortho(1, 5, -4, -1, -2, 9), mdn_orthographic(1, 5, -4, -1, -2, 9));
}

// The CIS367 lecture notes "Building models / Viewing" write the ortho matrix as P = S T with
//   T(-(left+right)/2, -(bottom+top)/2, (near+far)/2) and S(2/(right-left), 2/(top-bottom), 2/(near-far))
// and spells P out as rows
//   [2/(r-l), 0, 0, -(r+l)/(r-l);  0, 2/(t-b), 0, -(t+b)/(t-b);  0, 0, 2/(n-f), -(f+n)/(f-n);  0, 0, 0, 1].
// The slides have three typos that contradict their own S T derivation: S's first factor is printed 2/(left+right),
// P's [0][3] is printed -(right-left)/(right-left) and P's [2][3] loses its minus sign; the forms here are the ones
// S * T actually multiplies out to (and the ones glOrtho documents).
TEST(ProjectionTest, LectureOrthoIsScaleTimesTranslate) {
  const float l = -1, r = 3, b = -2, t = 2, n = 1, f = 10;
  const glm::mat4 st =
      scale({2 / (r - l), 2 / (t - b), 2 / (n - f)}) * translate({-(l + r) / 2, -(b + t) / 2, (n + f) / 2});
  const glm::mat4 expected = from_rows({2 / (r - l), 0, 0, -(r + l) / (r - l),  //
                                        0, 2 / (t - b), 0, -(t + b) / (t - b),  //
                                        0, 0, 2 / (n - f), -(f + n) / (f - n),  //
                                        0, 0, 0, 1});
  expect_mat_near(ortho(l, r, b, t, n, f), st);
  expect_mat_near(ortho(l, r, b, t, n, f), expected);
  // By hand: 2/4, 2/4, -2/9; translations -(3-1)/4 = -0.5, 0, -11/9.
  expect_mat_near(ortho(l, r, b, t, n, f), from_rows({0.5f, 0, 0, -0.5f, 0, 0.5f, 0, 0, 0, 0, -2.0f / 9, -11.0f / 9,  //
                                                      0, 0, 0, 1}));
  // The box's corners land on the NDC cube's corners, near at z = -1, far at z = +1.
  const glm::mat4 p = ortho(l, r, b, t, n, f);
  expect_vec_near(ndc(p, {l, b, -n}), {-1, -1, -1});
  expect_vec_near(ndc(p, {r, t, -n}), {1, 1, -1});
  expect_vec_near(ndc(p, {l, t, -f}), {-1, 1, 1});
  expect_vec_near(ndc(p, {r, b, -f}), {1, -1, 1});
}

// The CIS367 lecture, "Perspective matrices" and "frustum": the normalised perspective
//   N = [1 0 0 0; 0 1 0 0; 0 0 alpha beta; 0 0 -1 0], beta = 2 near far / (near - far),
// sends the near plane to z = -1 and the far plane to +1 only with alpha = -(near + far)/(far - near): the slide
// prints alpha without its minus sign (then near would land at -(n + 3f)/(f - n)). glFrustum is P = N S H: H
// shears the frustum's centre line onto -Z, S scales its sides to the planes x = +-z, y = +-z. Then
//   frustum = [2n/(r-l), 0, (r+l)/(r-l), 0;  0, 2n/(t-b), (t+b)/(t-b), 0;
//              0, 0, -(f+n)/(f-n), -2fn/(f-n);  0, 0, -1, 0]
// (the slide prints [0][2] as (right-left)/(right-left), a typo for (right+left)/(right-left)).
TEST(ProjectionTest, LectureFrustumIsNormalisationTimesScaleTimesShear) {
  const float l = -0.3f, r = 0.9f, b = -0.2f, t = 0.6f, n = 0.5f, f = 20;
  const float alpha = -(n + f) / (f - n), beta = 2 * n * f / (n - f);
  const glm::mat4 nn = from_rows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, alpha, beta, 0, 0, -1, 0});
  const glm::mat4 s = scale({2 * n / (r - l), 2 * n / (t - b), 1});
  glm::mat4 h(1.0f);
  h[2][0] = (l + r) / (2 * n);
  h[2][1] = (b + t) / (2 * n);
  const glm::mat4 expected = from_rows({2 * n / (r - l), 0, (r + l) / (r - l), 0,        //
                                        0, 2 * n / (t - b), (t + b) / (t - b), 0,        //
                                        0, 0, -(f + n) / (f - n), -2 * f * n / (f - n),  //
                                        0, 0, -1, 0});
  expect_mat_near(frustum(l, r, b, t, n, f), expected);
  expect_mat_near(frustum(l, r, b, t, n, f), nn * s * h);
  // By hand, frustum(-1, 3, -2, 2, 1, 10): 2/4, 2/4, (3-1)/4, -11/9, -20/9.
  expect_mat_near(frustum(-1, 3, -2, 2, 1, 10),
                  from_rows({0.5f, 0, 0.5f, 0, 0, 0.5f, 0, 0, 0, 0, -11.0f / 9, -20.0f / 9, 0, 0, -1, 0}));
  // The window corners on the near plane go to the near face of the NDC cube, the far corners (scaled by f/n
  // along their rays) to the far face.
  const glm::mat4 p = frustum(l, r, b, t, n, f);
  expect_vec_near(ndc(p, {l, b, -n}), {-1, -1, -1});
  expect_vec_near(ndc(p, {r, t, -n}), {1, 1, -1});
  expect_vec_near(ndc(p, {l * f / n, t * f / n, -f}), {-1, 1, 1}, 1e-4f);
  expect_vec_near(ndc(p, {r * f / n, b * f / n, -f}), {1, -1, 1}, 1e-4f);
  // Depth is monotonic between the planes.
  EXPECT_LT(ndc(p, {0, 0, -1}).z, ndc(p, {0, 0, -2}).z);
}

// The CIS367 lecture, "perspective":
//   P = [near/right, 0, 0, 0;  0, near/top, 0, 0;  0, 0, -(f+n)/(f-n), -2fn/(f-n);  0, 0, -1, 0]
// with top = near tan(fovy/2), right = top * aspect. Its "simple perspective" (90 degree field of view, sides on the
// planes x = +-z, y = +-z) is this with near/right = near/top = 1, i.e. exactly the normalisation N above.
TEST(ProjectionTest, LecturePerspectiveIsTheSymmetricFrustum) {
  for (float fovy_deg : {20.0f, 60.0f, 90.0f, 150.0f}) {
    const float fovy = glm::radians(fovy_deg), aspect = 1.6f, n = 0.2f, f = 75;
    const float top = n * std::tan(fovy / 2), right = top * aspect;
    const glm::mat4 expected = from_rows({n / right, 0, 0, 0, 0, n / top, 0, 0,  //
                                          0, 0, -(f + n) / (f - n), -2 * f * n / (f - n), 0, 0, -1, 0});
    expect_mat_near(perspective(fovy, aspect, n, f), expected, 1e-4f);
    expect_mat_near(perspective(fovy, aspect, n, f), frustum(-right, right, -top, top, n, f), 1e-4f);
  }
  const float n = 1, f = 9;
  const glm::mat4 simple =
      from_rows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -(n + f) / (f - n), 2 * n * f / (n - f), 0, 0, -1, 0});
  expect_mat_near(perspective(kPi / 2, 1.0f, n, f), simple);
  const glm::mat4 p = perspective(kPi / 2, 1.0f, n, f);
  expect_vec_near(ndc(p, {4, -4, -4}), {1, -1, ndc(p, {0, 0, -4}).z});  // on the planes x = -z, y = z
}

TEST(ProjectionTest, PerspectiveMapsTheFrustumOntoTheNdcCube) {
  const float fovy = glm::radians(50.0f), aspect = 16.0f / 9, n = 0.3f, f = 40;
  const glm::mat4 p = perspective(fovy, aspect, n, f);
  for (float d : {n, f}) {
    const float half_h = d * std::tan(fovy / 2), half_w = half_h * aspect;
    const float z = d == n ? -1.0f : 1.0f;
    expect_vec_near(ndc(p, {-half_w, -half_h, -d}), {-1, -1, z}, 1e-4f);
    expect_vec_near(ndc(p, {half_w, half_h, -d}), {1, 1, z}, 1e-4f);
    expect_vec_near(ndc(p, {0, 0, -d}), {0, 0, z}, 1e-4f);
  }
  // Hand-computed midpoint depth: z_ndc(-d) = (f + n)/(f - n) - 2fn/((f - n) d).
  const float d = 2.0f;
  EXPECT_NEAR(ndc(p, {0, 0, -d}).z, (f + n) / (f - n) - 2 * f * n / ((f - n) * d), 1e-5f);
}

glm::mat4 lecture_shear(float cot_theta, float cot_phi) {
  // The CIS367 lecture, "Shear matrix": H(theta, phi) = [1 0 -cot(theta) 0; 0 1 -cot(phi) 0; 0 0 1 0; 0 0 0 1].
  return from_rows({1, 0, -cot_theta, 0, 0, 1, -cot_phi, 0, 0, 0, 1, 0, 0, 0, 0, 1});
}

// The CIS367 lecture, "Oblique projection": P = M_orth S T H(theta, phi), i.e. ortho * shear.
TEST(ProjectionTest, ObliqueIsOrthoTimesLectureShear) {
  const float l = -2, r = 2, b = -2, t = 2, n = 1, f = 10;
  for (float angle_deg : {45.0f, 30.0f, 63.4f, 200.0f})
    for (float k : {1.0f, 0.5f, 0.25f}) {
      const float a = glm::radians(angle_deg);
      expect_mat_near(oblique(a, k, l, r, b, t, n, f),
                      ortho(l, r, b, t, n, f) * lecture_shear(k * std::cos(a), k * std::sin(a)));
    }
  expect_mat_near(oblique(0.7f, 0.0f, l, r, b, t, n, f), ortho(l, r, b, t, n, f));

  // Cabinet at 45 degrees, by hand: (0, 0, -4) is 4 units deep, drawn 0.5 * 4 = 2 units along (cos45, sin45),
  // i.e. eye (1.4142, 1.4142), NDC (0.7071, 0.7071) in this 4x4 window. Depth is ortho's.
  const glm::mat4 cabinet = oblique(kPi / 4, 0.5f, l, r, b, t, n, f);
  expect_vec_near(ndc(cabinet, {0, 0, -4}), {0.70710678f, 0.70710678f, ndc(ortho(l, r, b, t, n, f), {0, 0, -4}).z});
  // A unit edge receding into the screen is drawn depth_scale long at the receding angle; faces parallel to the
  // projection plane keep their shape (a unit square stays a unit square, in eye units of 2/(r-l) NDC).
  const glm::mat4 cavalier = oblique(glm::radians(30.0f), 1.0f, l, r, b, t, n, f);
  for (const auto& [m, k] : {std::pair{cabinet, 0.5f}, std::pair{cavalier, 1.0f}}) {
    const glm::vec3 p0 = ndc(m, {1, 1, -3}), p1 = ndc(m, {1, 1, -4});
    EXPECT_NEAR(glm::length(glm::vec2(p1 - p0)), k * 0.5f, 1e-5f);
    const glm::vec3 q = ndc(m, {2, 1, -3}), s = ndc(m, {1, 2, -3});
    expect_vec_near(q - p0, {0.5f, 0, 0});
    expect_vec_near(s - p0, {0, 0.5f, 0});
  }
  const glm::vec3 rec = ndc(cavalier, {0, 0, -2}) - ndc(cavalier, {0, 0, -1});
  EXPECT_NEAR(std::atan2(rec.y, rec.x), glm::radians(30.0f), 1e-5f);
}

TEST(ProjectionTest, ObliquePivotKeepsThatDepthInPlace) {
  const float l = -3, r = 3, b = -2, t = 2, n = 1, f = 20, pivot = 8;
  const glm::mat4 m = oblique(kPi / 4, 0.5f, l, r, b, t, n, f, pivot);
  const glm::mat4 o = ortho(l, r, b, t, n, f);
  expect_vec_near(ndc(m, {1.5f, -0.5f, -pivot}), ndc(o, {1.5f, -0.5f, -pivot}));
  expect_mat_near(m, o * translate({0, 0, -pivot}) * lecture_shear(0.5f * std::cos(kPi / 4), 0.5f * std::sin(kPi / 4)) *
                         translate({0, 0, pivot}));
}

// Length on screen of a unit world axis under a view rotation.
float foreshortening(const glm::mat4& view, glm::vec3 axis) {
  return glm::length(glm::vec2(view * glm::vec4(axis, 0)));
}

// A pure rotation; for the axonometric presets world +Y must also stay vertical (and upwards) on screen.
void expect_rotation(const glm::mat4& m, bool y_up = true) {
  const glm::mat3 r(m);
  expect_mat_near(glm::mat4(glm::transpose(r) * r), glm::mat4(1.0f));
  EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f);
  expect_vec_near(glm::vec3(m[3]), {0, 0, 0});
  if (!y_up) return;
  const glm::vec4 y = m * glm::vec4(0, 1, 0, 0);
  EXPECT_NEAR(y.x, 0.0f, 1e-6f);
  EXPECT_GT(y.y, 0.0f);
}

TEST(ProjectionTest, IsometricPresetIsTheLectureLookAtFromTheDiagonal) {
  const glm::mat4 v = isometric_view();
  expect_rotation(v);
  // The CIS367 lecture: "isometric view of cube aligned with axes": lookAt(eye (1,1,1), at (0,0,0), up (0,1,0));
  // the preset is its rotation (the translation back by sqrt3 removed).
  expect_mat_near(v, translate({0, 0, std::sqrt(3.0f)}) * look_at({1, 1, 1}, {0, 0, 0}, {0, 1, 0}));
  for (glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    EXPECT_NEAR(foreshortening(v, axis), std::sqrt(2.0f / 3.0f), 1e-6f);
  const glm::vec4 x = v * glm::vec4(1, 0, 0, 0), z = v * glm::vec4(0, 0, 1, 0);
  EXPECT_NEAR(glm::degrees(std::atan2(x.y, x.x)), -30.0f, 1e-4f);
  EXPECT_NEAR(glm::degrees(std::atan2(z.y, z.x)), -150.0f, 1e-4f);
}

TEST(ProjectionTest, DimetricAndTrimetricPresets) {
  const glm::mat4 d = dimetric_view();
  expect_rotation(d);
  EXPECT_NEAR(foreshortening(d, {1, 0, 0}), std::sqrt(5.0f / 8.0f), 1e-6f);
  EXPECT_NEAR(foreshortening(d, {0, 0, 1}), std::sqrt(5.0f / 8.0f), 1e-6f);
  EXPECT_NEAR(foreshortening(d, {0, 1, 0}), std::sqrt(3.0f) / 2, 1e-6f);
  const glm::vec4 x = d * glm::vec4(1, 0, 0, 0);
  EXPECT_NEAR(x.y / x.x, -0.5f, 1e-6f);  // the 2:1 pixel line

  const glm::mat4 t = trimetric_view();
  expect_rotation(t);
  const float fx = foreshortening(t, {1, 0, 0}), fy = foreshortening(t, {0, 1, 0}), fz = foreshortening(t, {0, 0, 1});
  EXPECT_NEAR(fx, 0.90138782f, 1e-5f);
  EXPECT_NEAR(fy, 0.86602540f, 1e-5f);
  EXPECT_NEAR(fz, 0.66143783f, 1e-5f);
  EXPECT_GT(std::abs(fx - fy), 0.02f);
  EXPECT_GT(std::abs(fy - fz), 0.02f);
  EXPECT_GT(std::abs(fx - fz), 0.02f);
}

TEST(ProjectionTest, MultiviewPresetsLookAlongTheDocumentedAxes) {
  EXPECT_EQ(front_view(), glm::mat4(1.0f));
  const glm::mat4 top = top_view(), side = side_view();
  expect_rotation(top, false);
  expect_rotation(side);
  // top: from +Y looking down; +X right, -Z up.
  EXPECT_EQ(glm::vec3(top * glm::vec4(0, 1, 0, 0)), glm::vec3(0, 0, 1));
  EXPECT_EQ(glm::vec3(top * glm::vec4(1, 0, 0, 0)), glm::vec3(1, 0, 0));
  EXPECT_EQ(glm::vec3(top * glm::vec4(0, 0, -1, 0)), glm::vec3(0, 1, 0));
  expect_mat_near(top, rotate_x(kPi / 2), 1e-6f);
  expect_mat_near(top, translate({0, 0, 1}) * look_at({0, 1, 0}, {0, 0, 0}, {0, 0, -1}), 1e-6f);
  // side: from +X looking towards -X; -Z right, +Y up.
  EXPECT_EQ(glm::vec3(side * glm::vec4(1, 0, 0, 0)), glm::vec3(0, 0, 1));
  EXPECT_EQ(glm::vec3(side * glm::vec4(0, 0, -1, 0)), glm::vec3(1, 0, 0));
  EXPECT_EQ(glm::vec3(side * glm::vec4(0, 1, 0, 0)), glm::vec3(0, 1, 0));
  expect_mat_near(side, rotate_y(-kPi / 2), 1e-6f);
  expect_mat_near(side, translate({0, 0, 1}) * look_at({1, 0, 0}, {0, 0, 0}, {0, 1, 0}), 1e-6f);
  // Third-angle layout: front and top share screen x, front and side share screen y.
  const glm::vec4 p(0.3f, -0.7f, 0.45f, 1.0f);
  EXPECT_FLOAT_EQ((front_view() * p).x, (top * p).x);
  EXPECT_FLOAT_EQ((front_view() * p).y, (side * p).y);
}

template <typename F>
void expect_invalid(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "no exception, expected one mentioning '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ProjectionTest, RejectsBadParameters) {
  expect_invalid([] { perspective(0.0f, 1, 0.1f, 10); }, "perspective: fovy");
  expect_invalid([] { perspective(kPi, 1, 0.1f, 10); }, "perspective: fovy");
  expect_invalid([] { perspective(kNaN, 1, 0.1f, 10); }, "perspective: fovy");
  expect_invalid([] { perspective(1, 0, 0.1f, 10); }, "perspective: aspect");
  expect_invalid([] { perspective(1, -2, 0.1f, 10); }, "perspective: aspect");
  expect_invalid([] { perspective(1, kInf, 0.1f, 10); }, "perspective: aspect");
  expect_invalid([] { perspective(1, 1, 0, 10); }, "perspective: near");
  expect_invalid([] { perspective(1, 1, -1, 10); }, "perspective: near");
  expect_invalid([] { perspective(1, 1, 1, 1); }, "perspective: far");
  expect_invalid([] { perspective(1, 1, 2, 1); }, "perspective: far");
  expect_invalid([] { perspective(1, 1, 0.1f, kInf); }, "perspective: far");

  expect_invalid([] { frustum(1, 1, -1, 1, 1, 10); }, "frustum: left");
  expect_invalid([] { frustum(-1, 1, 2, 2, 1, 10); }, "frustum: bottom");
  expect_invalid([] { frustum(-1, 1, -1, 1, 0, 10); }, "frustum: near");
  expect_invalid([] { frustum(-1, 1, -1, 1, -1, 10); }, "frustum: near");
  expect_invalid([] { frustum(-1, 1, -1, 1, 5, 5); }, "frustum: far");
  expect_invalid([] { frustum(kNaN, 1, -1, 1, 1, 10); }, "frustum: left");
  expect_invalid([] { frustum(-1, 1, -1, kInf, 1, 10); }, "frustum: top");

  expect_invalid([] { ortho(2, 2, -1, 1, 1, 10); }, "ortho: left");
  expect_invalid([] { ortho(-1, 1, 0, 0, 1, 10); }, "ortho: bottom");
  expect_invalid([] { ortho(-1, 1, -1, 1, 3, 3); }, "ortho: far");
  expect_invalid([] { ortho(-1, 1, -1, 1, 3, 2); }, "ortho: far");
  expect_invalid([] { ortho(-1, 1, -1, 1, kNaN, 2); }, "ortho: near");
  EXPECT_NO_THROW(ortho(-1, 1, -1, 1, -5, 5));   // glOrtho allows planes behind the eye
  EXPECT_NO_THROW(frustum(1, -1, -1, 1, 1, 5));  // and mirrored windows

  expect_invalid([] { oblique(kNaN, 1, -1, 1, -1, 1, 1, 10); }, "oblique: angle");
  expect_invalid([] { oblique(1, -0.5f, -1, 1, -1, 1, 1, 10); }, "oblique: depth_scale");
  expect_invalid([] { oblique(1, kInf, -1, 1, -1, 1, 1, 10); }, "oblique: depth_scale");
  expect_invalid([] { oblique(1, 1, -1, 1, -1, 1, 1, 10, kNaN); }, "oblique: pivot_distance");
  expect_invalid([] { oblique(1, 1, -1, -1, -1, 1, 1, 10); }, "oblique: left");
  expect_invalid([] { oblique(1, 1, -1, 1, -1, 1, 10, 1); }, "oblique: far");
}

}  // namespace
}  // namespace facet::projection_tests
