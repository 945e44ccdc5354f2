// test_splats.cpp - render_splats against the 3D Gaussian Splatting paper's formulas, evaluated here independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "facet/camera.hpp"
#include "facet/cpu_level.hpp"
#include "facet/framebuffer.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/splats.hpp"

namespace facet::splats_tests {
namespace {

constexpr float kSh0 = 0.28209479177387814f;
constexpr int kSize = 64;
const glm::vec4 kBackground(0.2f, 0.3f, 0.4f, 1.0f);

// One Gaussian per call; `color` is the displayed colour (degree 0).
void add(GaussianSplats& s, glm::vec3 position, glm::vec3 scale, glm::quat rotation, float opacity, glm::vec3 color) {
  s.positions.push_back(position);
  s.scales.push_back(scale);
  s.rotations.push_back(rotation);
  s.opacities.push_back(opacity);
  s.sh.push_back((color - 0.5f) / kSh0);
}

// Looking down -z from z = 5 at the origin.
View orthographic_view(float half_extent) {
  View v;
  v.view_from_world = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  v.clip_from_view = glm::ortho(-half_extent, half_extent, -half_extent, half_extent, 1.0f, 10.0f);
  v.near = 1.0f, v.far = 10.0f;
  return v;
}

View perspective_view() {
  View v;
  v.view_from_world = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
  v.clip_from_view = glm::perspective(glm::radians(30.0f), 1.0f, 1.0f, 10.0f);
  v.near = 1.0f, v.far = 10.0f;
  return v;
}

Framebuffer draw(const GaussianSplats& splats, const View& view, int threads = 2) {
  Renderer renderer(threads);
  Framebuffer target(kSize, kSize);
  renderer.clear(target, kBackground, 1.0f);
  renderer.finish(target);
  render_splats(renderer, target, view, splats);
  return target;
}

// The paper's alpha of a 2D Gaussian of screen covariance `cov` (low-pass added here) at offset d from its centre.
float paper_alpha(glm::mat2 cov, glm::vec2 d, float opacity) {
  cov[0][0] += 0.3f, cov[1][1] += 0.3f;
  const float power = -0.5f * glm::dot(d, glm::inverse(cov) * d);
  const float alpha = std::min(0.99f, opacity * std::exp(power));
  return power > 0.0f || alpha < 1.0f / 255.0f ? 0.0f : alpha;
}

// Every channel of every pixel within one step of 255 of `expected(x, y)`: the tolerance of 8-bit rounding.
template <class Expected>
void expect_image(const Framebuffer& target, Expected&& expected) {
  int off = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec4 got = unpack_rgba8(target.pixel(x, y)) * 255.0f, want = expected(x, y) * 255.0f;
      for (int c = 0; c < 4; ++c)
        if (std::abs(got[c] - want[c]) > 1.0f && off++ < 5)
          ADD_FAILURE() << "pixel (" << x << ", " << y << ") channel " << c << ": " << got[c] << " against " << want[c];
    }
  EXPECT_EQ(off, 0);
}

TEST(Splats, OneRotatedGaussianIsItsAnalytic2DGaussian) {
  // Orthographic, half-extent 1 over 64 pixels: world x maps to 32 pixels a unit, world y to -32.
  GaussianSplats s;
  const float angle = glm::radians(30.0f);
  const glm::quat about_z = glm::angleAxis(angle, glm::vec3(0, 0, 1));
  const glm::vec3 scale(0.12f, 0.05f, 0.02f), color(1.0f, 0.5f, 0.0f);
  add(s, glm::vec3(0.1f, -0.05f, 0.0f), scale, about_z, 0.9f, color);
  const Framebuffer target = draw(s, orthographic_view(1.0f));

  const glm::mat2 rotation(std::cos(angle), std::sin(angle), -std::sin(angle), std::cos(angle));
  const glm::mat2 world = rotation * glm::mat2(scale.x * scale.x, 0, 0, scale.y * scale.y) * glm::transpose(rotation);
  const glm::mat2 jacobian(32.0f, 0.0f, 0.0f, -32.0f);
  const glm::mat2 screen = jacobian * world * glm::transpose(jacobian);
  const glm::vec2 centre(32.0f + 0.1f * 32.0f, 32.0f + 0.05f * 32.0f);
  expect_image(target, [&](int x, int y) {
    const float a = paper_alpha(screen, glm::vec2(x + 0.5f, y + 0.5f) - centre, 0.9f);
    return glm::vec4(color * a + glm::vec3(kBackground) * (1.0f - a), a + (1.0f - a) * kBackground.a);
  });
  // The footprint is the rotated ellipse's: wider along 30 degrees (up and to the right on screen) than across.
  EXPECT_NE(target.pixel(38, 28), target.pixel(38, 40));
}

TEST(Splats, PerspectiveScalesTheFootprintByFocalLengthOverDepth) {
  GaussianSplats s;
  const glm::vec3 color(0.0f, 0.8f, 0.3f);
  add(s, glm::vec3(0.0f), glm::vec3(0.08f, 0.08f, 0.08f), glm::quat(1, 0, 0, 0), 0.7f, color);
  const Framebuffer target = draw(s, perspective_view());
  const float focal = 32.0f / std::tan(glm::radians(15.0f)) / 5.0f;  // pixels per world unit at depth 5
  const float sigma2 = 0.08f * 0.08f * focal * focal;
  expect_image(target, [&](int x, int y) {
    const float a = paper_alpha(glm::mat2(sigma2, 0, 0, sigma2), glm::vec2(x + 0.5f, y + 0.5f) - 32.0f, 0.7f);
    return glm::vec4(color * a + glm::vec3(kBackground) * (1.0f - a), a + (1.0f - a) * kBackground.a);
  });
}

TEST(Splats, OverlappingSplatsCompositeNearestFirstWhateverTheirOrder) {
  const glm::vec3 red(1, 0, 0), blue(0, 0, 1), scale(0.2f, 0.2f, 0.2f);
  const glm::quat none(1, 0, 0, 0);
  GaussianSplats near_first, far_first, swapped;
  add(near_first, glm::vec3(0, 0, 1), scale, none, 0.6f, red);
  add(near_first, glm::vec3(0, 0, -1), scale, none, 0.6f, blue);
  add(far_first, glm::vec3(0, 0, -1), scale, none, 0.6f, blue);
  add(far_first, glm::vec3(0, 0, 1), scale, none, 0.6f, red);
  add(swapped, glm::vec3(0, 0, -1), scale, none, 0.6f, red);
  add(swapped, glm::vec3(0, 0, 1), scale, none, 0.6f, blue);
  const View view = orthographic_view(1.0f);
  const Framebuffer a = draw(near_first, view), b = draw(far_first, view), c = draw(swapped, view);
  EXPECT_TRUE(std::equal(a.color().begin(), a.color().end(), b.color().begin()));
  // Both have the same footprint (orthographic): over the background, red * a + blue * a (1 - a).
  const float sigma2 = 0.2f * 0.2f * 32.0f * 32.0f;
  expect_image(a, [&](int x, int y) {
    const float al = paper_alpha(glm::mat2(sigma2, 0, 0, sigma2), glm::vec2(x + 0.5f, y + 0.5f) - 32.0f, 0.6f);
    const glm::vec3 rgb = red * al + blue * al * (1 - al) + glm::vec3(kBackground) * (1 - al) * (1 - al);
    return glm::vec4(rgb, 1.0f);
  });
  const glm::vec4 centre_a = unpack_rgba8(a.pixel(32, 32)), centre_c = unpack_rgba8(c.pixel(32, 32));
  EXPECT_GT(centre_a.r, centre_a.b);
  EXPECT_GT(centre_c.b, centre_c.r);
}

TEST(Splats, TheImageIsTheSameAtAnyThreadCount) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), positive(0.01f, 0.15f), chance(0.0f, 1.0f);
  GaussianSplats s;
  s.sh_degree = 1;
  for (int i = 0; i < 400; ++i) {
    s.positions.emplace_back(unit(random), unit(random), unit(random));
    s.scales.emplace_back(positive(random), positive(random), positive(random));
    s.rotations.push_back(glm::normalize(glm::quat(unit(random), unit(random), unit(random), unit(random))));
    s.opacities.push_back(chance(random));
    for (int k = 0; k < 4; ++k) s.sh.emplace_back(unit(random), unit(random), unit(random));
  }
  const Framebuffer one = draw(s, perspective_view(), 1);
  for (int threads : {2, 3, 5}) {
    const Framebuffer many = draw(s, perspective_view(), threads);
    EXPECT_TRUE(std::equal(one.color().begin(), one.color().end(), many.color().begin())) << threads << " threads";
  }
}

TEST(Splats, EveryCpuLevelBlendsTheSameBytes) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), positive(0.02f, 0.2f), chance(0.0f, 1.0f);
  GaussianSplats s;
  for (int i = 0; i < 300; ++i)
    add(s, glm::vec3(unit(random), unit(random), unit(random)), glm::vec3(positive(random), positive(random), 0.05f),
        glm::normalize(glm::quat(unit(random), unit(random), unit(random), unit(random))), chance(random),
        glm::vec3(chance(random), chance(random), chance(random)));
  const std::string saved = cpu_level();
  std::vector<std::uint32_t> first;
  for (const std::string& level : cpu_levels()) {
    set_cpu_level(level);
    const Framebuffer target = draw(s, perspective_view());
    const std::vector<std::uint32_t> bytes(target.color().begin(), target.color().end());
    if (first.empty()) first = bytes;
    EXPECT_EQ(bytes, first) << level;
  }
  set_cpu_level(saved);
  const std::uint32_t background = pack_rgba8(kBackground);
  EXPECT_GT(std::count_if(first.begin(), first.end(), [&](std::uint32_t c) { return c != background; }), 500);
}

TEST(Splats, ColourFollowsTheSphericalHarmonicsOfTheViewDirection) {
  GaussianSplats s;
  s.sh_degree = 1;
  s.positions.emplace_back(0.0f);
  s.scales.emplace_back(0.1f);
  s.rotations.emplace_back(1, 0, 0, 0);
  s.opacities.push_back(1.0f);
  // DC 0.2 in red; the degree-1 term along y, whose basis function is -0.4886 y.
  s.sh = {glm::vec3(0.2f, 0.0f, 0.0f), glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
  const float base = kSh0 * 0.2f + 0.5f, term = 0.4886025f * 0.5f;
  EXPECT_NEAR(splat_color(s, 0, glm::vec3(0, 1, 0)).r, base - term, 1e-6f);
  EXPECT_NEAR(splat_color(s, 0, glm::vec3(0, -1, 0)).r, base + term, 1e-6f);
  EXPECT_NEAR(splat_color(s, 0, glm::vec3(1, 0, 0)).r, base, 1e-6f);
  EXPECT_EQ(splat_color(s, 0, glm::vec3(1, 0, 0)).g, 0.5f);
  s.sh[0] = glm::vec3(-5.0f);  // a negative colour is clamped at 0
  EXPECT_EQ(splat_color(s, 0, glm::vec3(1, 0, 0)), glm::vec3(0.0f));
}

TEST(Splats, ASplatBehindASurfaceIsHiddenAndOneInFrontShows) {
  // A square at z = 0 facing the camera, one Gaussian in front of it on the left, one behind it on the right.
  auto square = std::make_shared<Mesh>();
  square->positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  square->indices = {0, 1, 2, 0, 2, 3};
  square->colors.assign(4, glm::vec4(0, 0, 1, 1));  // blue, so that the red splat shows
  auto splats = std::make_shared<GaussianSplats>();
  add(*splats, glm::vec3(-0.5f, 0, 1), glm::vec3(0.1f), glm::quat(1, 0, 0, 0), 0.9f, glm::vec3(1, 0, 0));
  add(*splats, glm::vec3(0.5f, 0, -1), glm::vec3(0.1f), glm::quat(1, 0, 0, 0), 0.9f, glm::vec3(1, 0, 0));
  auto cloud = std::make_shared<Mesh>();
  cloud->positions = splats->positions;
  cloud->splats = splats;
  SceneOptions options;
  options.shading = Shading::unlit;
  const View view = orthographic_view(1.5f);
  const auto render = [&](bool with_splats) {
    Scene scene;
    scene.add(Instance{square});
    if (with_splats) scene.add(Instance{cloud});
    Renderer renderer(2);
    Framebuffer target(kSize, kSize);
    target.keep_depth(false);  // the scene keeps it where splats need it
    renderer.clear(target, kBackground, 1.0f);
    scene.render(renderer, target, view, options);
    return std::vector<std::uint32_t>(target.color().begin(), target.color().end());
  };
  const std::vector<std::uint32_t> plain = render(false), mixed = render(true);
  const auto at = [](int x, int y) { return static_cast<std::size_t>(y) * kSize + x; };
  // Left Gaussian's centre: world x -0.5 is pixel 21.3; right one's, pixel 42.7.
  EXPECT_NE(mixed[at(21, 32)], plain[at(21, 32)]);
  EXPECT_EQ(mixed[at(42, 32)], plain[at(42, 32)]);
  EXPECT_GT(unpack_rgba8(mixed[at(21, 32)]).r, unpack_rgba8(plain[at(21, 32)]).r);
}

// Where the target keeps depth, a pixel the Gaussians cover at least half takes their blended view depth: one
// Gaussian covers exactly the pixels whose paper alpha reaches 0.5, at its centre's depth; two overlapping at
// different depths give the alpha-weighted mean; a surface in front keeps its own depth.
TEST(Splats, APixelTheyCoverAtLeastHalfTakesTheirBlendedDepth) {
  const View view = orthographic_view(1.0f);  // depth 5 at z = 0; window depth (d - 1) / 9
  const auto window = [](float distance) { return (distance - 1.0f) / 9.0f; };
  GaussianSplats one;
  const glm::vec3 scale(0.1f, 0.06f, 0.05f);
  add(one, glm::vec3(0.0f, 0.0f, 0.5f), scale, glm::quat(1, 0, 0, 0), 0.9f, glm::vec3(1.0f));
  Renderer renderer(2);
  Framebuffer target(kSize, kSize);
  renderer.clear(target, kBackground, 1.0f);
  renderer.finish(target);
  render_splats(renderer, target, view, one);
  const glm::mat2 screen(32.0f * 32.0f * scale.x * scale.x, 0.0f, 0.0f, 32.0f * 32.0f * scale.y * scale.y);
  int covered = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float alpha = paper_alpha(screen, glm::vec2(x + 0.5f, y + 0.5f) - glm::vec2(32.0f), 0.9f);
      if (std::abs(alpha - 0.5f) < 0.01f) continue;  // rounding may put it either side
      const float depth = target.depth_at(x, y);
      if (alpha > 0.5f) {
        EXPECT_NEAR(depth, window(4.5f), 1e-6f) << x << "," << y;
        ++covered;
      } else {
        EXPECT_EQ(depth, 1.0f) << x << "," << y;
      }
    }
  EXPECT_GT(covered, 15);  // about 24 pixels, the ellipse where alpha reaches 0.5, less those on its rim

  // Two on one axis, 0.5 apart in depth: the nearer has weight alpha1, the farther alpha2 (1 - alpha1).
  GaussianSplats two = one;
  add(two, glm::vec3(0.0f, 0.0f, 0.0f), scale, glm::quat(1, 0, 0, 0), 0.9f, glm::vec3(1.0f));
  renderer.clear(target, kBackground, 1.0f);
  renderer.finish(target);
  render_splats(renderer, target, view, two);
  const float a = paper_alpha(screen, glm::vec2(0.5f, 0.5f), 0.9f), near_weight = a, far_weight = a * (1.0f - a);
  EXPECT_NEAR(target.depth_at(32, 32), window((4.5f * near_weight + 5.0f * far_weight) / (near_weight + far_weight)),
              1e-5f);

  // A surface nearer than the Gaussian: the Gaussian is hidden there and the depth stays the surface's.
  renderer.clear(target, kBackground, window(4.0f));
  renderer.finish(target);
  render_splats(renderer, target, view, one);
  EXPECT_EQ(target.depth_at(32, 32), window(4.0f));
}

}  // namespace
}  // namespace facet::splats_tests
