// test_interpolation.cpp - perspective-correct interpolation against the analytic answer on a grazing checkerboard.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/draw.hpp"
#include "facet/renderer.hpp"
#include "support/test_shaders.hpp"

namespace facet::test {
namespace {

struct CheckerResult {
  int compared = 0, wrong = 0;
};

// A floor plane y = -1 from z = -1.5 to z = -40 seen from the origin: two big triangles, uv = (x, z) / 2.
CheckerResult render_floor(bool affine) {
  const int width = 320, height = 200;
  const float fovy = glm::radians(60.0f), aspect = float(width) / height;
  CheckerShader shader;
  shader.clip_from_object = glm::perspective(fovy, aspect, 0.5f, 100.0f);
  shader.affine = affine;
  shader.cells = 1.0f;
  const float x0 = -20, x1 = 20, z0 = -1.5f, z1 = -40;
  const std::vector<CheckerShader::Vertex> quad = {{{x0, -1, z0}, glm::vec2(x0, z0) / 2.0f},
                                                   {{x1, -1, z0}, glm::vec2(x1, z0) / 2.0f},
                                                   {{x1, -1, z1}, glm::vec2(x1, z1) / 2.0f},
                                                   {{x0, -1, z1}, glm::vec2(x0, z1) / 2.0f}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  Renderer renderer(2);
  Framebuffer fb(width, height);
  renderer.clear(fb, glm::vec4(0.5f, 0.0f, 0.0f, 1.0f));
  renderer.draw(fb, shader, std::span<const CheckerShader::Vertex>(quad), indices);
  renderer.finish(fb);

  CheckerResult r;
  const float tan_half = std::tan(fovy / 2);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // The eye ray through the pixel centre meets the floor at t = -1 / dir.y.
      const float ndc_x = 2.0f * (x + 0.5f) / width - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / height;
      const glm::vec3 dir(ndc_x * tan_half * aspect, ndc_y * tan_half, -1.0f);
      if (dir.y >= 0.0f) continue;
      const glm::vec3 hit = dir * (-1.0f / dir.y);
      if (hit.z < z1 + 1 || hit.z > z0 - 0.05f || hit.x < x0 + 0.05f || hit.x > x1 - 0.05f) continue;
      const glm::vec2 uv = glm::vec2(hit.x, hit.z) / 2.0f;
      // Skip pixels near a cell border (their footprint straddles it) and far away where cells alias.
      const float footprint = std::abs(hit.z) * 2.0f * tan_half / height;  // world size of one pixel, roughly
      const float step = footprint * std::abs(hit.z) / 1.0f;               // grazing stretch along z
      if (step > 0.25f) continue;
      const glm::vec2 f = uv - glm::floor(uv);
      const float margin = std::max(0.02f, step);
      if (std::min({f.x, 1 - f.x, f.y, 1 - f.y}) < margin) continue;
      const int parity = (static_cast<int>(std::floor(uv.x)) + static_cast<int>(std::floor(uv.y))) & 1;
      const bool white = (fb.pixel(x, y) & 0xff) > 128;
      ++r.compared;
      r.wrong += white != (parity == 1);
    }
  return r;
}

TEST(Interpolation, PerspectiveCorrectMatchesAnalyticCheckerboard) {
  const CheckerResult r = render_floor(false);
  ASSERT_GT(r.compared, 5000);
  EXPECT_EQ(r.wrong, 0) << r.wrong << " of " << r.compared << " pixels show the wrong cell";
}

TEST(Interpolation, AffineInterpolationFailsTheSameCheck) {
  const CheckerResult r = render_floor(true);
  ASSERT_GT(r.compared, 5000);
  EXPECT_GT(r.wrong, r.compared / 10) << "affine interpolation should visibly bend the checkerboard";
}

}  // namespace
}  // namespace facet::test
