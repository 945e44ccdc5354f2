// test_cloud_looks.cpp - the looks of clouds: eye-dome lighting against its formula and as bare clouds' default,
// the height colour map, and the points' material and lighting.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/splats.hpp"
#include "support/scratch_dir.hpp"

namespace facet::cloud_looks_tests {
namespace {

constexpr int kSize = 48;

// A bare cloud: a near square of points (z = 0, half the view wide) in front of a far one (z = -1) that fills it.
Mesh two_layers() {
  Mesh m;
  const auto layer = [&](float z, float half, int n) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.points.push_back(static_cast<std::uint32_t>(m.positions.size()));
        m.positions.emplace_back(-half + 2.0f * half * i / (n - 1), -half + 2.0f * half * j / (n - 1), z);
      }
  };
  layer(-1.0f, 2.0f, 120);
  layer(0.0f, 0.5f, 40);
  return m;
}

struct Drawn {
  Framebuffer fb{kSize, kSize};
  View view;
};

void draw(Drawn& out, float strength) {
  Scene scene;
  scene.add(Instance{std::make_shared<Mesh>(two_layers()), glm::mat4(1.0f)});
  out.view.view_from_world = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
  out.view.clip_from_view = glm::perspective(glm::radians(60.0f), 1.0f, 0.5f, 10.0f);
  SceneOptions options;
  options.shading = Shading::unlit;
  options.color = glm::vec4(0.8f, 0.6f, 0.4f, 1.0f);
  options.point_size = 3.0f;
  options.eye_dome_lighting = strength;
  Renderer renderer(2);
  renderer.clear(out.fb, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f);
  scene.render(renderer, out.fb, out.view, options);
}

int channel(std::uint32_t rgba, int c) { return static_cast<int>((rgba >> (8 * c)) & 0xffu); }

// Every pixel against the formula computed here from the kept depth: the base-2 log of each pixel's linear depth,
// the mean over its drawn 8-neighbours of max(0, own - theirs), the colour scaled by exp(-300 strength mean).
// Pixels of the far layer at the near one's border darken (partly at a low strength, to black at a high one); flat
// regions and the background keep their colours.
TEST(EyeDomeLighting, EveryPixelFollowsTheFormula) {
  Drawn off;
  draw(off, 0.0f);
  for (const float strength : {0.01f, 2.0f}) {
    SCOPED_TRACE("strength " + std::to_string(strength));
    Drawn on;
    draw(on, strength);
    const std::vector<float> depth = linear_depth(on.fb, on.view.clip_from_view);
    const auto log_at = [&](int x, int y) { return std::log2(depth[static_cast<std::size_t>(y) * kSize + x]); };
    int darkened = 0, partly = 0, kept = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const std::uint32_t before = off.fb.pixel(x, y), after = on.fb.pixel(x, y);
        if (depth[static_cast<std::size_t>(y) * kSize + x] == 0.0f) {
          EXPECT_EQ(after, before) << x << "," << y;  // background
          continue;
        }
        float sum = 0.0f;
        int count = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= kSize || ny >= kSize) continue;
            if (depth[static_cast<std::size_t>(ny) * kSize + nx] == 0.0f) continue;
            sum += std::max(0.0f, log_at(x, y) - log_at(nx, ny));
            ++count;
          }
        const float shade = std::exp(-300.0f * strength * (count ? sum / count : 0.0f));
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(channel(after, c), channel(before, c) * shade, 0.51f) << x << "," << y << " channel " << c;
        EXPECT_EQ(channel(after, 3), channel(before, 3));
        (shade > 0.99f ? kept : shade > 0.5f ? partly : darkened) += 1;
      }
    EXPECT_GT(strength < 1.0f ? partly : darkened, 20);  // the far layer's ring around the near one
    EXPECT_GT(kept, 500);                                 // both layers' flat insides
  }
}

TEST(EyeDomeLighting, AStrengthOutOfRangeIsRefused) {
  Drawn out;
  EXPECT_THROW(draw(out, -1.0f), std::invalid_argument);
  EXPECT_THROW(draw(out, kMaxEyeDomeLighting * 2.0f), std::invalid_argument);
  EXPECT_THROW(draw(out, std::nanf("")), std::invalid_argument);
}

// The bytes of a render of `model` into `out` (a PNG, or a GIF for a turntable), with the strength given; `views`
// asks for a contact sheet of those views, `turntable` for a turntable of that many frames.
std::string render_cloud(const std::filesystem::path& model, const std::filesystem::path& out,
                         std::optional<float> strength, std::vector<SheetView> views = {}, int turntable = 0) {
  RenderJob job;
  job.model = model;
  job.width = 64;
  job.height = 48;
  job.outputs.color = out;
  job.look.eye_dome_lighting = strength;
  job.views = std::move(views);
  job.turntable = turntable;
  Renderer renderer(2);
  render(job, renderer);
  std::ifstream in(out, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// `facet render` lights a bare cloud (no normals, no colours) with eye-dome lighting unless told otherwise, and
// leaves a coloured one as it is.
TEST(EyeDomeLighting, ABareCloudGetsItByDefault) {
  const std::filesystem::path dir = test::scratch_dir("eye_dome_lighting");
  std::ofstream bare(dir / "bare.xyz"), coloured(dir / "coloured.xyz");
  const Mesh cloud = two_layers();
  for (const glm::vec3& p : cloud.positions) {
    bare << p.x << ' ' << p.y << ' ' << p.z << '\n';
    coloured << p.x << ' ' << p.y << ' ' << p.z << " 200 150 100\n";
  }
  bare.close();
  coloured.close();
  const auto as_default = render_cloud(dir / "bare.xyz", dir / "a.png", std::nullopt);
  EXPECT_EQ(as_default, render_cloud(dir / "bare.xyz", dir / "b.png", kDefaultEyeDomeLighting));
  EXPECT_NE(as_default, render_cloud(dir / "bare.xyz", dir / "c.png", 0.0f));
  EXPECT_EQ(render_cloud(dir / "coloured.xyz", dir / "d.png", std::nullopt),
            render_cloud(dir / "coloured.xyz", dir / "e.png", 0.0f));
  EXPECT_NE(render_cloud(dir / "coloured.xyz", dir / "f.png", std::nullopt),
            render_cloud(dir / "coloured.xyz", dir / "g.png", 1.0f));
  // Contact sheets and turntables take the same default.
  const std::vector<SheetView> views = {SheetView::front, SheetView::top};
  const auto sheet = render_cloud(dir / "bare.xyz", dir / "h.png", std::nullopt, views);
  EXPECT_EQ(sheet, render_cloud(dir / "bare.xyz", dir / "i.png", kDefaultEyeDomeLighting, views));
  EXPECT_NE(sheet, render_cloud(dir / "bare.xyz", dir / "j.png", 0.0f, views));
  const auto turn = render_cloud(dir / "bare.xyz", dir / "k.gif", std::nullopt, {}, 3);
  EXPECT_EQ(turn, render_cloud(dir / "bare.xyz", dir / "l.gif", kDefaultEyeDomeLighting, {}, 3));
  EXPECT_NE(turn, render_cloud(dir / "bare.xyz", dir / "m.gif", 0.0f, {}, 3));
}

}  // namespace
}  // namespace facet::cloud_looks_tests

namespace facet::cloud_looks_tests {
namespace {

// The height colour map: the lowest vertex blue, the highest red, the stops between at quarter heights, along the
// up axis asked for; it replaces the model's colours and refuses a colour for the whole model beside it.
TEST(ColorMap, HeightRunsFromBlueAtTheBottomToRedAtTheTop) {
  Mesh mesh;
  for (int k = 0; k <= 4; ++k) mesh.positions.emplace_back(0.3f * k, 0.0f, -2.0f + k);  // z from -2 to 2
  mesh.positions.emplace_back(0.0f, std::nanf(""), 0.0f);
  mesh.points = {0, 1, 2, 3, 4, 5};
  mesh.colors.assign(mesh.positions.size(), glm::vec4(0.5f));
  LookSpec look;
  look.color_map = ColorMap::height;
  Mesh by_z = mesh;
  apply_color_map(by_z, look, UpAxis::pos_z);
  const glm::vec4 stops[] = {{0, 0, 1, 1}, {0, 1, 1, 1}, {0, 1, 0, 1}, {1, 1, 0, 1}, {1, 0, 0, 1}};
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(by_z.colors[k], stops[k]) << k;
  EXPECT_EQ(by_z.colors[5], stops[0]);  // no height: the lowest colour
  Mesh by_negative_x = mesh;
  apply_color_map(by_negative_x, look, UpAxis::neg_x);  // x falls as z rises: the order turns over
  for (int k = 0; k <= 4; ++k) EXPECT_EQ(by_negative_x.colors[k], stops[4 - k]) << k;
  Mesh untouched = mesh;
  apply_color_map(untouched, LookSpec{}, UpAxis::pos_z);
  EXPECT_EQ(untouched.colors, mesh.colors);
  look.color = glm::vec3(1.0f, 0.0f, 0.0f);
  EXPECT_THROW(apply_color_map(by_z, look, UpAxis::pos_z), std::invalid_argument);
}

// The intensity colour map: grey from black at the weakest return to white at the strongest, a non-finite
// intensity black; a mesh without intensities is refused, naming what would give them.
TEST(ColorMap, IntensityRunsFromBlackToWhite) {
  Mesh mesh;
  for (int k = 0; k < 4; ++k) mesh.positions.emplace_back(static_cast<float>(k), 0.0f, 0.0f);
  mesh.points = {0, 1, 2, 3};
  LookSpec look;
  look.color_map = ColorMap::intensity;
  try {
    apply_color_map(mesh, look, UpAxis::pos_y);
    ADD_FAILURE() << "a mesh without intensities was coloured";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the model has no intensities"), std::string::npos) << e.what();
  }
  mesh.intensities = {200.0f, 100.0f, 150.0f, std::nanf("")};
  apply_color_map(mesh, look, UpAxis::pos_y);
  ASSERT_EQ(mesh.colors.size(), 4u);
  EXPECT_EQ(mesh.colors[0], glm::vec4(1, 1, 1, 1));
  EXPECT_EQ(mesh.colors[1], glm::vec4(0, 0, 0, 1));
  EXPECT_EQ(mesh.colors[2], glm::vec4(0.5f, 0.5f, 0.5f, 1));
  EXPECT_EQ(mesh.colors[3], glm::vec4(0, 0, 0, 1));
}

}  // namespace
}  // namespace facet::cloud_looks_tests

namespace facet::cloud_looks_tests {
namespace {

// --world-point-size: a square of side s in the model's units at distance d along the view axis covers s P[1][1]
// H / (2 d) pixels a side under a perspective projection, the same at every distance under an orthographic one.
TEST(WorldPointSize, ASquareCoversWhatItsSizeSpansAtItsDistance) {
  for (const bool perspective : {true, false}) {
    SCOPED_TRACE(perspective ? "perspective" : "orthographic");
    Mesh cloud;
    cloud.positions = {{-1.0f, 0.0f, -1.0f}, {1.2f, 0.0f, 1.0f}};  // 4 and 2 from the eye at z = 3
    cloud.points = {0, 1};
    Scene scene;
    scene.add(Instance{std::make_shared<Mesh>(cloud), glm::mat4(1.0f)});
    View view;
    view.view_from_world = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
    view.clip_from_view = perspective ? glm::perspective(glm::radians(60.0f), 4.0f / 3.0f, 0.5f, 10.0f)
                                      : glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.5f, 10.0f);
    SceneOptions options;
    options.shading = Shading::unlit;
    options.point_size = 0.3f;
    options.world_point_size = true;
    Framebuffer fb(160, 120);
    Renderer renderer(1);
    renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), 1.0f);
    scene.render(renderer, fb, view, options);
    for (const float distance : {4.0f, 2.0f}) {
      const float expected = 0.3f * view.clip_from_view[1][1] * 120.0f * 0.5f / (perspective ? distance : 1.0f);
      // The square's width along its centre row, on its own half of the image.
      const bool left = distance == 4.0f;
      int widest = 0;
      for (int y = 0; y < 120; ++y) {
        int width = 0;
        for (int x = left ? 0 : 80; x < (left ? 80 : 160); ++x) width += fb.pixel(x, y) != fb.pixel(0, 0);
        widest = std::max(widest, width);
      }
      EXPECT_NEAR(widest, expected, 1.0f) << "distance " << distance;
    }
  }
}

}  // namespace
}  // namespace facet::cloud_looks_tests

namespace facet::cloud_looks_tests {
namespace {

// The default strength: the look's when it sets one, else on for a bare cloud alone (not for normals, colours,
// triangles or splats beside the points).
TEST(EyeDomeLighting, OnByDefaultForABareCloudAlone) {
  Mesh bare;
  bare.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  bare.points = {0, 1, 2};
  LookSpec look;
  EXPECT_EQ(eye_dome_lighting_for(look, bare), kDefaultEyeDomeLighting);
  Mesh coloured = bare, with_normals = bare, with_triangles = bare, with_splats = bare;
  coloured.colors.assign(3, glm::vec4(1.0f));
  with_normals.normals.assign(3, glm::vec3(0, 0, 1));
  with_triangles.indices = {0, 1, 2};
  with_splats.splats = std::make_shared<GaussianSplats>();
  for (const Mesh* mesh : {&coloured, &with_normals, &with_triangles, &with_splats})
    EXPECT_EQ(eye_dome_lighting_for(look, *mesh), 0.0f);
  look.eye_dome_lighting = 3.0f;
  EXPECT_EQ(eye_dome_lighting_for(look, bare), 3.0f);
  EXPECT_EQ(eye_dome_lighting_for(look, coloured), 3.0f);
}

// One point of material colour seen head-on, under one directional light from `towards_light`; the centre pixel.
std::uint32_t one_point(Mesh mesh, Shading shading, glm::vec3 towards_light) {
  Scene scene;
  scene.add(Instance{std::make_shared<Mesh>(std::move(mesh)), glm::mat4(1.0f)});
  View view;
  view.view_from_world = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
  view.clip_from_view = glm::perspective(glm::radians(40.0f), 1.0f, 0.5f, 10.0f);
  SceneOptions options;
  options.shading = shading;
  options.point_size = 5.0f;
  options.ambient = glm::vec3(0.0f);
  options.lights = {Light{.vector = towards_light, .intensity = 3.0f}};
  Framebuffer fb(kSize, kSize);
  Renderer renderer(1);
  renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), 1.0f);
  scene.render(renderer, fb, view, options);
  return fb.color()[static_cast<std::size_t>(kSize / 2 * kSize + kSize / 2)];
}

Mesh point_of(std::int32_t point_material, bool pyrender_lighting) {
  Mesh m;
  m.positions = {{0, 0, 0}};
  m.points = {0};
  Material red;
  red.diffuse = glm::vec4(0.9f, 0.1f, 0.1f, 1.0f);
  red.pyrender_lighting = pyrender_lighting;
  m.materials = {red};
  m.point_material = point_material;
  return m;
}

// Points are drawn in Mesh::point_material (the default white without one); validate() refuses an index past the
// materials.
TEST(PointMaterial, PointsTakeTheirMaterial) {
  const std::uint32_t red = one_point(point_of(0, false), Shading::unlit, {0, 0, 1});
  EXPECT_GT(channel(red, 0), 200);
  EXPECT_LT(channel(red, 1), 60);
  const std::uint32_t white = one_point(point_of(-1, false), Shading::unlit, {0, 0, 1});
  EXPECT_GT(channel(white, 1), 200);
  Mesh bad = point_of(1, false);
  EXPECT_THROW(validate(bad, "cloud.ply"), InputError);
}

// Without normals points are drawn unlit, but under pyrender's lighting they are lit as facing the eye: brighter
// under a light from the eye than under one from the side, and darker than unlit under a grazing one.
TEST(PointMaterial, PyrenderLightsPointsWithoutNormalsAsFacingTheEye) {
  const auto red = [](std::uint32_t c) { return channel(c, 0); };
  const int front = red(one_point(point_of(0, true), Shading::automatic, {0, 0, 1}));
  const int side = red(one_point(point_of(0, true), Shading::automatic, {1, 0, 0.2f}));
  EXPECT_GT(front, side + 60);
  const int unlit_front = red(one_point(point_of(0, false), Shading::automatic, {0, 0, 1}));
  const int unlit_side = red(one_point(point_of(0, false), Shading::automatic, {1, 0, 0.2f}));
  EXPECT_EQ(unlit_front, unlit_side);
}

}  // namespace
}  // namespace facet::cloud_looks_tests
