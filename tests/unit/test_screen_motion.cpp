// test_screen_motion.cpp - the motion buffer against points projected at both moments, and through the CLI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <stdexcept>
#include <vector>

#include "facet/model.hpp"
#include "facet/render_job.hpp"
#include "support/npy.hpp"
#include "support/scratch_dir.hpp"

namespace facet::screen_motion_tests {
namespace {

namespace fs = std::filesystem;

// A 4 x 4 square in the plane z = 0, facing +z, split into two triangles.
std::shared_ptr<Mesh> square() {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  mesh->indices = {0, 1, 2, 0, 2, 3};
  return mesh;
}

SurfaceIds ids_of(Scene& scene, const View& view, int width, int height) {
  Renderer renderer(2);
  Framebuffer target(width, height);
  return scene.render_ids(renderer, target, view, SceneOptions{});
}

// Where a world point lands on the image, in pixels from the top-left corner: the test's own projection.
glm::vec2 pixel_of(const View& view, glm::vec3 p, int width, int height) {
  const glm::vec4 clip = view.clip_from_view * view.view_from_world * glm::vec4(p, 1.0f);
  return {(clip.x / clip.w + 1.0f) * 0.5f * width, (1.0f - clip.y / clip.w) * 0.5f * height};
}

TEST(ScreenMotion, ASlideSeenOrthographicallyIsItsDistanceInPixels) {
  // 4 x 3 world units onto 80 x 60 pixels: 20 pixels a unit.
  const View view{glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0)),
                  glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.1f, 10.0f)};
  Scene now, later;
  now.add(Instance{square(), glm::mat4(1.0f)});
  later.add(Instance{square(), glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.25f, 0.0f))});
  const SurfaceIds ids = ids_of(now, view, 80, 60);
  const std::vector<glm::vec2> motion = screen_motion(now, ids, view, later, view);
  ASSERT_EQ(motion.size(), 80u * 60u);
  for (std::size_t p = 0; p < motion.size(); ++p) {
    ASSERT_NE(ids.instance[p], kNoSurface);  // the square fills the view
    EXPECT_NEAR(motion[p].x, 10.0f, 1e-3f) << p;
    EXPECT_NEAR(motion[p].y, -5.0f, 1e-3f) << p;  // up in the world is up the image: -y
  }
}

TEST(ScreenMotion, ATurnSeenInPerspectiveMovesEachPointWhereItsProjectionGoes) {
  const int width = 64, height = 48;
  const View view{glm::lookAt(glm::vec3(0, 0, 6), glm::vec3(0), glm::vec3(0, 1, 0)),
                  glm::perspective(0.8f, 64.0f / 48.0f, 0.1f, 20.0f)};
  // The later frame: the square turned 20 degrees about y and lifted, seen from a camera a little to the right.
  const glm::mat4 moved =
      glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.3f, 0)) * glm::rotate(glm::mat4(1.0f), 0.35f, glm::vec3(0, 1, 0));
  const View later_view{glm::lookAt(glm::vec3(0.5f, 0, 6), glm::vec3(0), glm::vec3(0, 1, 0)), view.clip_from_view};
  Scene now, later;
  now.add(Instance{square(), glm::mat4(1.0f)});
  later.add(Instance{square(), moved});
  const SurfaceIds ids = ids_of(now, view, width, height);
  const std::vector<glm::vec2> motion = screen_motion(now, ids, view, later, later_view);
  const glm::vec3 eye(0, 0, 6);
  int checked = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * width + x;
      if (ids.instance[p] == kNoSurface) {
        EXPECT_EQ(motion[p], glm::vec2(0.0f));
        continue;
      }
      // The point under the pixel centre: the eye's ray through it meets the plane z = 0.
      const glm::vec4 far = glm::inverse(view.clip_from_view * view.view_from_world) *
                            glm::vec4(2.0f * (x + 0.5f) / width - 1.0f, 1.0f - 2.0f * (y + 0.5f) / height, 1.0f, 1.0f);
      const glm::vec3 direction = glm::vec3(far) / far.w - eye;
      const glm::vec3 point = eye + direction * (-eye.z / direction.z);
      const glm::vec2 want = pixel_of(later_view, glm::vec3(moved * glm::vec4(point, 1.0f)), width, height) -
                             glm::vec2(x + 0.5f, y + 0.5f);
      EXPECT_NEAR(glm::length(motion[p] - want), 0.0f, 2e-3f) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, width * height / 4);
}

TEST(ScreenMotion, ScenesOfOtherInstancesOrTrianglesAreRefused) {
  const View view{glm::mat4(1.0f), glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, -1.0f, 1.0f)};
  Scene now, two, other;
  now.add(Instance{square(), glm::mat4(1.0f)});
  two.add(Instance{square(), glm::mat4(1.0f)});
  two.add(Instance{square(), glm::mat4(1.0f)});
  auto fewer = square();
  fewer->indices.resize(3);
  other.add(Instance{fewer, glm::mat4(1.0f)});
  const SurfaceIds ids = ids_of(now, view, 8, 8);
  EXPECT_THROW(screen_motion(now, ids, view, two, view), std::invalid_argument);
  EXPECT_THROW(screen_motion(now, ids, view, other, view), std::invalid_argument);
  SurfaceIds cut = ids;
  cut.instance.pop_back();
  EXPECT_THROW(screen_motion(now, cut, view, now, view), std::invalid_argument);
}

// --output-motion of the two-bone model of simple_skin: the rendered motion at each pixel agrees with the mesh posed
// at both moments, and a frame's motion carries its pixels onto the next frame's surface.
TEST(ScreenMotion, TheRenderJobWritesTheMotionOfTheAnimation) {
  const fs::path dir = test::scratch_dir("motion");
  RenderJob job;
  job.model = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
  job.width = 96;
  job.height = 72;
  job.animation.time = 0.7;  // between the keys of 45 and 90 degrees
  job.outputs.motion = dir / "motion.npy";
  job.outputs.mask = dir / "mask.png";
  Renderer renderer(2);
  render(job, renderer);
  const test::Npy npy = test::read_npy(job.outputs.motion);
  EXPECT_NE(npy.header.find("'descr': '<f4'"), std::string::npos) << npy.header;
  EXPECT_NE(npy.header.find("'shape': (72, 96, 2)"), std::string::npos) << npy.header;
  ASSERT_EQ(npy.words.size(), 96u * 72u * 2u);
  std::vector<float> motion(npy.words.size());
  std::memcpy(motion.data(), npy.words.data(), 4 * motion.size());
  // The skin's upper half turns about the joint at y = 1 while its lower half stays: some pixels move, some do not.
  int moving = 0, still = 0, drawn = 0;
  for (std::size_t p = 0; p < 96u * 72u; ++p) {
    const float dx = motion[2 * p], dy = motion[2 * p + 1];
    ASSERT_TRUE(std::isfinite(dx) && std::isfinite(dy));
    if (dx == 0.0f && dy == 0.0f) continue;
    ++drawn;
    (std::hypot(dx, dy) > 0.05f ? moving : still) += 1;
  }
  EXPECT_GT(moving, 20);
  EXPECT_GT(still, 20);
  EXPECT_GT(drawn, 200);
  // A model without animations does not move: its motion is zero wherever it is drawn.
  job.model = "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  job.animation = {};
  render(job, renderer);
  for (const std::uint32_t v : test::read_npy(job.outputs.motion).words) ASSERT_EQ(v, 0u);  // +0.0f
}

}  // namespace
}  // namespace facet::screen_motion_tests
