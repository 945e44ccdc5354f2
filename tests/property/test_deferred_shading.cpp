// test_deferred_shading.cpp - deferred shading (visibility pass, then one shading pass) draws what immediate does.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

Framebuffer render(const ClipMesh& m, int width, int height, RenderState state, bool deferred, int threads) {
  state.defer_shading = deferred;
  return render_colors(m, width, height, state, threads);
}

void expect_same(const Framebuffer& a, const Framebuffer& b) {
  ASSERT_EQ(a.color().size(), b.color().size());
  std::size_t colour_diffs = 0, depth_diffs = 0, first = a.color().size();
  for (std::size_t i = 0; i < a.color().size(); ++i) {
    if (a.color()[i] != b.color()[i]) colour_diffs++, first = std::min(first, i);
    if (a.depth()[i] != b.depth()[i]) depth_diffs++, first = std::min(first, i);
  }
  EXPECT_EQ(colour_diffs, 0u) << "first differing pixel " << first % a.width() << "," << first / a.width();
  EXPECT_EQ(depth_diffs, 0u) << "first differing pixel " << first % a.width() << "," << first / a.width();
}

TEST(DeferredShading, SphereMatchesImmediateBitForBit) {
  const glm::mat4 clip_from_object = glm::perspective(glm::radians(50.0f), 4.0f / 3.0f, 0.5f, 10.0f) *
                                     glm::translate(glm::mat4(1), glm::vec3(0.2f, -0.1f, -3.0f));
  const ClipMesh sphere = closed_sphere(24, 32, clip_from_object);
  RenderState state;
  for (const int threads : {1, 3}) expect_same(render(sphere, 203, 150, state, false, threads), render(sphere, 203, 150, state, true, threads));
}

}  // namespace
}  // namespace facet::test
