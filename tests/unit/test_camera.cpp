// test_camera.cpp - VTK-style camera helpers, sphere framing and azimuth/elevation turns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "facet/camera.hpp"
#include "facet/projection.hpp"
#include "facet/transform.hpp"
#include "support/matrix_asserts.hpp"

namespace facet::camera_tests {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

using test::expect_mat_near;
using test::expect_vec_near;

glm::vec3 ndc(const glm::mat4& clip_from_world, glm::vec3 p) {
  const glm::vec4 c = clip_from_world * glm::vec4(p, 1.0f);
  EXPECT_GT(c.w, 0.0f);
  return glm::vec3(c) / c.w;
}

TEST(CameraTest, DefaultsAndMatrices) {
  const Camera cam;
  expect_vec_near(cam.position, {0, 0, 1});
  expect_vec_near(cam.focal_point, {0, 0, 0});
  expect_vec_near(cam.view_up, {0, 1, 0});
  EXPECT_EQ(cam.view_angle_degrees, 30.0f);
  expect_mat_near(view_from_world(cam), translate({0, 0, -1}));
  const Camera c{{3, 4, 5}, {1, 0, -1}, {0, 0, 1}, 40.0f, 0.5f, 50.0f};
  expect_mat_near(view_from_world(c), look_at({3, 4, 5}, {1, 0, -1}, {0, 0, 1}));
  expect_mat_near(clip_from_view(c, 1.5f), perspective(glm::radians(40.0f), 1.5f, 0.5f, 50.0f));
  EXPECT_THROW(view_from_world(Camera{{1, 1, 1}, {1, 1, 1}}), std::invalid_argument);
  EXPECT_THROW(clip_from_view(Camera{.view_angle_degrees = 0.0f}, 1.0f), std::invalid_argument);
  EXPECT_THROW(clip_from_view(Camera{.near = 0.0f}, 1.0f), std::invalid_argument);
}

// Points of the sphere that a frame must keep inside NDC: the 6 ends of the camera axes, the 6 ends of the world
// axes, the 8 points towards the bounding-box corners, the 4 silhouette (tangent) points that are the true extremes
// on screen, and a random scatter over the surface.
std::vector<glm::vec3> sphere_probe_points(const Camera& cam, glm::vec3 c, float r) {
  const glm::vec3 back = glm::normalize(cam.position - c);
  const glm::vec3 right = glm::normalize(glm::cross(cam.view_up, back)), up = glm::cross(back, right);
  std::vector<glm::vec3> pts;
  for (glm::vec3 axis : {right, up, back, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
    pts.push_back(c + r * axis);
    pts.push_back(c - r * axis);
  }
  for (int i = 0; i < 8; ++i)
    pts.push_back(c + r / std::sqrt(3.0f) * glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  // Tangent point: seen from the eye at distance d, at angle asin(r/d) off the axis; it sits r^2/d towards the eye
  // from the centre and r sqrt(1 - r^2/d^2) sideways.
  const float d = glm::length(cam.position - c);
  for (glm::vec3 side : {right, -right, up, -up})
    pts.push_back(c + back * (r * r / d) + side * (r * std::sqrt(1 - r * r / (d * d))));
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  for (int i = 0; i < 500; ++i) pts.push_back(c + r * glm::normalize(glm::vec3(g(rng), g(rng), g(rng))));
  return pts;
}

TEST(CameraTest, FrameSphereKeepsTheSphereInsideTheViewWithAMargin) {
  struct Case {
    glm::vec3 center;
    float radius, aspect, angle;
    glm::vec3 direction, up;
  };
  const Case cases[] = {
      {{0, 0, 0}, 1.0f, 1.0f, 30.0f, {0, 0, 1}, {0, 1, 0}},
      {{5, -2, 3}, 2.5f, 16.0f / 9, 30.0f, {1, 1, 1}, {0, 1, 0}},
      {{0, 0, 0}, 0.01f, 0.5f, 45.0f, {-2, 0.5f, 3}, {0, 1, 0}},
      {{100, 0, 0}, 40.0f, 2.0f, 60.0f, {0, -1, 0.2f}, {0, 0, 1}},
      {{1, 2, 3}, 1.0f, 1.0f, 120.0f, {0, 0, -5}, {1, 1, 0}},
      {{0, 0, 0}, 3.0f, 0.3f, 10.0f, {1, 0, 0}, {0, 1, 0}},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(testing::Message() << "radius " << k.radius << " aspect " << k.aspect << " angle " << k.angle);
    const Camera cam = frame_sphere(k.center, k.radius, k.aspect, k.angle, k.direction, k.up);
    expect_vec_near(cam.focal_point, k.center);
    expect_vec_near(glm::normalize(cam.position - k.center), glm::normalize(k.direction), 1e-5f);
    EXPECT_NEAR(glm::dot(glm::normalize(cam.view_up), glm::normalize(k.direction)), 0.0f, 1e-5f);
    EXPECT_EQ(cam.view_angle_degrees, k.angle);
    // near/far hug the sphere as documented.
    const float d = glm::length(cam.position - k.center);
    EXPECT_NEAR(cam.near, std::max(d - 1.05f * k.radius, 1e-3f * d), 1e-4f * d);
    EXPECT_NEAR(cam.far, d + 1.05f * k.radius, 1e-4f * d);
    // Distance by hand: the silhouette half-angle a has tan a = tan(half view) / 1.08 on the tighter axis, and
    // d = r / sin a = r sqrt(1 + tan^2 a) / tan a.
    const float tv = std::tan(glm::radians(k.angle) / 2), ta = std::min(tv, tv * k.aspect) / 1.08f;
    EXPECT_NEAR(d, k.radius * std::sqrt(1 + ta * ta) / ta, 1e-4f * d);

    const glm::mat4 clip_from_world = clip_from_view(cam, k.aspect) * view_from_world(cam);
    float max_x = 0, max_y = 0;
    for (glm::vec3 p : sphere_probe_points(cam, k.center, k.radius)) {
      const glm::vec3 q = ndc(clip_from_world, p);
      EXPECT_LE(std::abs(q.x), 1.0f);
      EXPECT_LE(std::abs(q.y), 1.0f);
      EXPECT_GE(q.z, -1.0f);
      EXPECT_LE(q.z, 1.0f);
      max_x = std::max(max_x, std::abs(q.x));
      max_y = std::max(max_y, std::abs(q.y));
    }
    // It fills the view nicely: the tighter axis is used to ~1/1.08 = 92.6%, within the 5-10% margin.
    EXPECT_NEAR(std::max(max_x, max_y), 1.0f / 1.08f, 2e-3f);
  }
}

TEST(CameraTest, FrameSphereRejectsBadInput) {
  EXPECT_THROW(frame_sphere({0, 0, 0}, 0.0f, 1, 30, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, -1.0f, 1, 30, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, 1, 0, 30, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, 1, 1, 0, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, 1, 1, 180, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, 1, 1, 30, {0, 0, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, 1, 1, 30, {0, 2, 0}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({kNaN, 0, 0}, 1, 1, 30, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(frame_sphere({0, 0, 0}, kNaN, 1, 30, {0, 0, 1}, {0, 1, 0}), std::invalid_argument);
}

TEST(CameraTest, AzimuthAndElevationFollowVtk) {
  Camera cam{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
  apply_azimuth_elevation(cam, 90, 0);  // Azimuth(90): the camera swings to its right, onto +X
  expect_vec_near(cam.position, {5, 0, 0});
  expect_vec_near(cam.view_up, {0, 1, 0});

  cam = Camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
  apply_azimuth_elevation(cam, 0, 90);  // Elevation(90): straight above, looking down, up now towards -Z
  expect_vec_near(cam.position, {0, 5, 0});
  expect_vec_near(cam.view_up, {0, 0, -1});
  EXPECT_NO_THROW(view_from_world(cam));

  cam = Camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
  apply_azimuth_elevation(cam, 0, 30);  // by hand: (0, 5 sin30, 5 cos30), up tilted back by 30
  expect_vec_near(cam.position, {0, 2.5f, 4.3301270f});
  expect_vec_near(cam.view_up, {0, 0.8660254f, -0.5f});

  // Around a focal point away from the origin, with azimuth first: the point on the sphere about it at that
  // azimuth (about +Y, from +Z towards +X) and elevation, looking at it with +Y up.
  for (float az : {-120.0f, 10.0f, 75.0f})
    for (float el : {-60.0f, 0.0f, 45.0f}) {
      const glm::vec3 fp(2, -1, 4);
      Camera c{fp + glm::vec3(0, 0, 3), fp, {0, 1, 0}};
      apply_azimuth_elevation(c, az, el);
      const float a = glm::radians(az), e = glm::radians(el);
      const glm::vec3 eye = fp + 3.0f * glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
      expect_vec_near(c.position, eye, 1e-5f);
      expect_vec_near(c.focal_point, fp);
      EXPECT_NEAR(glm::length(c.view_up), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::dot(c.view_up, glm::normalize(fp - c.position)), 0.0f, 1e-5f);
      expect_mat_near(view_from_world(c), look_at(eye, fp, {0, 1, 0}), 1e-5f);
    }

  // A view_up that is not perpendicular to the view direction comes back orthogonalised (f3d's
  // OrthogonalizeViewUp), the position untouched.
  Camera tilted{{1, 2, 6}, {0, 1, 0}, {0, 1, 0}};
  apply_azimuth_elevation(tilted, 0, 0);
  expect_vec_near(tilted.position, {1, 2, 6});
  expect_vec_near(tilted.view_up, glm::normalize(glm::vec3(-1, 37, -6)), 1e-5f);  // Y minus its part along (1,1,6)

  // About a perpendicular view_up, azimuths add and a full turn comes back.
  Camera a{{1, 2, 6}, {0, 1, 0}, {0, 6, -1}}, b = a;
  apply_azimuth_elevation(a, 25, 0);
  apply_azimuth_elevation(a, 40, 0);
  apply_azimuth_elevation(b, 65, 0);
  expect_vec_near(a.position, b.position, 1e-5f);
  apply_azimuth_elevation(b, 295, 0);
  expect_vec_near(b.position, {1, 2, 6}, 1e-5f);
  // Elevating through the pole keeps a usable camera.
  Camera over{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}};
  apply_azimuth_elevation(over, 0, 120);
  expect_vec_near(over.position, {0, 5 * std::sin(glm::radians(120.0f)), 5 * std::cos(glm::radians(120.0f))});
  EXPECT_NO_THROW(view_from_world(over));
}

TEST(CameraTest, AzimuthElevationRejectsBadInput) {
  Camera cam;
  EXPECT_THROW(apply_azimuth_elevation(cam, kNaN, 0), std::invalid_argument);
  EXPECT_THROW(apply_azimuth_elevation(cam, 0, std::numeric_limits<float>::infinity()), std::invalid_argument);
  Camera same{{1, 1, 1}, {1, 1, 1}, {0, 1, 0}};
  EXPECT_THROW(apply_azimuth_elevation(same, 10, 10), std::invalid_argument);
  Camera parallel{{0, 5, 0}, {0, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(apply_azimuth_elevation(parallel, 10, 10), std::invalid_argument);
  Camera no_up{{0, 0, 5}, {0, 0, 0}, {0, 0, 0}};
  EXPECT_THROW(apply_azimuth_elevation(no_up, 10, 10), std::invalid_argument);
}

}  // namespace
}  // namespace facet::camera_tests
