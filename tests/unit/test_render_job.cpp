// test_render_job.cpp - the library's render description: up axes, framing, make_view, looks, and render().
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/primitives.hpp"
#include "facet/render_job.hpp"
#include "support/npy.hpp"
#include "support/scratch_dir.hpp"

namespace facet::render_job_tests {
namespace {

const std::filesystem::path kBox = "/usr/share/assimp/models/OBJ/box.obj";

// Where a world point lands in NDC under the view.
glm::vec3 ndc(const View& view, glm::vec3 p) {
  const glm::vec4 c = view.clip_from_view * view.view_from_world * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

bool inside_ndc(glm::vec3 p) { return std::abs(p.x) <= 1.0f && std::abs(p.y) <= 1.0f && std::abs(p.z) <= 1.0f; }

TEST(UpAxis, ParsesSignedAndBareAxes) {
  EXPECT_EQ(parse_up_axis("+Y"), UpAxis::pos_y);
  EXPECT_EQ(parse_up_axis("-z"), UpAxis::neg_z);
  EXPECT_EQ(parse_up_axis("Z"), UpAxis::pos_z);
  EXPECT_EQ(parse_up_axis(" +x "), UpAxis::pos_x);
  EXPECT_EQ(parse_up_axis("up"), std::nullopt);
  EXPECT_EQ(parse_up_axis("+W"), std::nullopt);
  EXPECT_EQ(parse_up_axis(""), std::nullopt);
}

TEST(UpAxis, EveryAxisIsTurnedToPlusY) {
  const std::pair<UpAxis, glm::vec3> axes[] = {{UpAxis::pos_x, {1, 0, 0}}, {UpAxis::neg_x, {-1, 0, 0}},
                                               {UpAxis::pos_y, {0, 1, 0}}, {UpAxis::neg_y, {0, -1, 0}},
                                               {UpAxis::pos_z, {0, 0, 1}}, {UpAxis::neg_z, {0, 0, -1}}};
  for (const auto& [axis, direction] : axes) {
    const glm::mat3 r = upright_from_model(axis);
    EXPECT_EQ(r * direction, glm::vec3(0, 1, 0));
    EXPECT_FLOAT_EQ(glm::determinant(r), 1.0f);  // a rotation, not a mirror
  }
}

TEST(Framing, SphereAboutTheBoxCentreThroughTheFarthestVertex) {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 4, 0}};
  mesh.indices = {0, 1, 2};
  const Framing f = framing_of(mesh, "m");
  EXPECT_EQ(f.center, glm::vec3(1, 2, 0));
  EXPECT_FLOAT_EQ(f.radius, std::sqrt(5.0f));
  mesh.positions[2] = {0, 3e38f, 0};
  mesh.positions[1] = {0, -3e38f, 0};
  try {
    framing_of(mesh, "huge.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "huge.obj");
    EXPECT_NE(e.problem().find("too large to frame"), std::string::npos);
  }
}

TEST(MakeView, EveryProjectionFramesTheWholeModel) {
  const Framing framing{{1, -2, 3}, 0.5f};
  for (int p = 0; p <= static_cast<int>(Projection::side); ++p) {
    CameraSpec spec;
    spec.projection = static_cast<Projection>(p);
    const View view = make_view(spec, framing, 4.0f / 3.0f);
    for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
      for (const float s : {-1.0f, 1.0f}) {
        const glm::vec3 p_ndc = ndc(view, framing.center + s * framing.radius * d);
        EXPECT_TRUE(inside_ndc(p_ndc)) << "projection " << p << " point " << p_ndc.x << "," << p_ndc.y << ","
                                       << p_ndc.z;
      }
    EXPECT_NEAR(ndc(view, framing.center).x, 0.0f, 1e-4f) << "projection " << p;
  }
}

TEST(MakeView, DefaultViewKeepsTheModelUpAxisUpOnScreen) {
  for (const auto& [axis, up] :
       {std::pair{UpAxis::pos_y, glm::vec3(0, 1, 0)}, std::pair{UpAxis::pos_z, glm::vec3(0, 0, 1)},
        std::pair{UpAxis::neg_x, glm::vec3(-1, 0, 0)}}) {
    CameraSpec spec;
    spec.up = axis;
    const View view = make_view(spec, {{0, 0, 0}, 1.0f}, 1.0f);
    EXPECT_GT(ndc(view, 0.5f * up).y, 0.2f);
    EXPECT_LT(ndc(view, -0.5f * up).y, -0.2f);
  }
}

TEST(MakeView, AnExplicitCameraLooksFromWhereItIsPut) {
  CameraSpec spec;
  spec.position = glm::vec3(0, 0, 5);
  spec.focal_point = glm::vec3(0, 0, 0);
  const View view = make_view(spec, {{0, 0, 0}, 1.0f}, 1.0f);
  EXPECT_NEAR(glm::vec3(view.view_from_world * glm::vec4(0, 0, 0, 1)).z, -5.0f, 1e-5f);
  EXPECT_NEAR(view.near, 5.0f - 1.05f, 1e-5f);
  EXPECT_NEAR(view.far, 5.0f + 1.05f, 1e-5f);
}

TEST(MakeView, RefusesDegenerateCameras) {
  const Framing framing{{0, 0, 0}, 1.0f};
  CameraSpec at_focal;
  at_focal.position = at_focal.focal_point = glm::vec3(1, 1, 1);
  EXPECT_THROW(make_view(at_focal, framing, 1.0f), std::invalid_argument);
  CameraSpec zero_near;
  zero_near.near = 0.0f;
  EXPECT_THROW(make_view(zero_near, framing, 1.0f), std::invalid_argument);
  CameraSpec far_before_near;
  far_before_near.near = 5.0f;
  far_before_near.far = 1.0f;
  EXPECT_THROW(make_view(far_before_near, framing, 1.0f), std::invalid_argument);
  CameraSpec empty_window;
  empty_window.projection = Projection::frustum;
  empty_window.frustum_window = std::array<float, 4>{1, 1, -1, 1};
  EXPECT_THROW(make_view(empty_window, framing, 1.0f), std::invalid_argument);
}

TEST(Look, OptionsAndClearColourFollowTheSpec) {
  LookSpec look;
  look.shading = Shading::flat;
  look.cull = CullMode::none;
  look.painter = true;
  look.color = glm::vec3(0.2f, 0.4f, 0.6f);
  look.light_direction = glm::vec3(0, 0, 2);
  const SceneOptions options = scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f));
  EXPECT_EQ(options.shading, Shading::flat);
  EXPECT_EQ(options.cull, CullMode::none);
  EXPECT_TRUE(options.painter);
  EXPECT_EQ(options.color, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
  EXPECT_EQ(options.lights.at(0).vector, glm::vec3(0, 0, 2));
  EXPECT_EQ(clear_color(look, glm::vec3(0.5f)), glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
  look.transparent_background = true;
  look.background = glm::vec3(1, 0, 0);
  EXPECT_EQ(clear_color(look, glm::vec3(0.5f)), glm::vec4(1, 0, 0, 0));
  look.light_direction = glm::vec3(0.0f);
  EXPECT_THROW(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f)), std::invalid_argument);
}

// pyrender's lighting, as the Python renderer asks for it: the caller's lights and an ambient colour, no
// environment and no headlight, in every shading; without an ambient colour the caller's lights join the model's.
TEST(Look, AnAmbientColourLightsByTheCallersLightsAlone) {
  LookSpec look;
  look.ambient = glm::vec3(0.1f, 0.2f, 0.3f);
  SceneOptions options = scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f));
  EXPECT_EQ(options.environment, nullptr);
  EXPECT_EQ(options.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_TRUE(options.lights.empty());
  look.shading = Shading::gouraud;
  EXPECT_TRUE(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f)).lights.empty());
  const Light spot{Light::Kind::spot, glm::vec3(0, 1, 0), glm::vec3(1.0f), 5.0f};
  look.lights = {spot};
  options = scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f));
  ASSERT_EQ(options.lights.size(), 1u);
  EXPECT_EQ(options.lights[0].kind, Light::Kind::spot);

  LookSpec studio;
  studio.lights = {spot};
  const Light file_light{Light::Kind::point, glm::vec3(0, 0, 1), glm::vec3(1.0f), 2.0f};
  options = scene_options(studio, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f), std::span(&file_light, 1));
  EXPECT_NE(options.environment, nullptr);
  ASSERT_EQ(options.lights.size(), 2u);
  EXPECT_EQ(options.lights[0].kind, Light::Kind::point);
  EXPECT_EQ(options.lights[1].kind, Light::Kind::spot);
  studio.lights.clear();
  studio.shading = Shading::gouraud;
  EXPECT_EQ(scene_options(studio, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f)).lights.size(), 1u);

  look.ambient = glm::vec3(-0.1f, 0.0f, 0.0f);
  EXPECT_THROW(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f)), std::invalid_argument);
  look.ambient = glm::vec3(std::nanf(""), 0.0f, 0.0f);
  EXPECT_THROW(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f)), std::invalid_argument);
}

TEST(Look, WireframeOnALightBackgroundIsDark) {
  LookSpec look;
  look.wireframe = true;
  EXPECT_FALSE(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.1f)).color);
  EXPECT_EQ(scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.9f)).color,
            glm::vec4(0.1f, 0.1f, 0.1f, 1.0f));
}

TEST(Render, WritesTheImageAndDepthOfTheFramedModel) {
  const std::filesystem::path dir = test::scratch_dir("render_job");
  RenderJob job;
  job.model = kBox;
  job.width = 64;
  job.height = 48;
  job.outputs = {dir / "box.png", dir / "box.npy"};
  Renderer renderer(2);
  render(job, renderer);
  int width = 0, height = 0;
  const std::vector<std::uint8_t> rgba = read_png(dir / "box.png", width, height);
  ASSERT_EQ(width, 64);
  ASSERT_EQ(height, 48);
  // The framed box covers the centre and leaves the corners to the background.
  const auto pixel = [&](int x, int y) {
    return glm::ivec3(rgba[(y * 64 + x) * 4], rgba[(y * 64 + x) * 4 + 1], rgba[(y * 64 + x) * 4 + 2]);
  };
  const glm::ivec3 background = glm::ivec3(glm::round(kDefaultBackground * 255.0f));
  EXPECT_EQ(pixel(0, 0), background);
  EXPECT_NE(pixel(32, 24), background);
  EXPECT_TRUE(std::filesystem::file_size(dir / "box.npy") > 64u * 48u * 4u);
}

TEST(Render, AFailedRenderLeavesNoFile) {
  const std::filesystem::path dir = test::scratch_dir("render_job");
  RenderJob job;
  job.model = kBox;
  job.width = 32;
  job.height = 32;
  job.outputs = {dir / "box.png", dir / "no-such-folder" / "box.npy"};
  Renderer renderer(1);
  EXPECT_ANY_THROW(render(job, renderer));
  EXPECT_FALSE(std::filesystem::exists(dir / "box.png"));

  job.outputs = {dir / "same.png", dir / "same.png"};
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.outputs = {dir / "box.png", {}};
  job.width = 0;
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.width = 32;
  job.model = dir / "missing.obj";
  EXPECT_THROW(render(job, renderer), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// Depth plus the camera model turn every drawn pixel back into a point on the surface: the unit box's faces.
TEST(CameraModel, DepthBackProjectsToTheSurfaceDrawn) {
  for (const Projection projection : {Projection::perspective, Projection::frustum}) {
    Scene scene;
    scene.add(Instance{std::make_shared<Mesh>(load_model(kBox)), glm::mat4(1.0f)});
    CameraSpec spec;
    spec.projection = projection;
    spec.azimuth_degrees = 20.0f;
    const int width = 96, height = 64;
    const View view = make_view(spec, {{0, 0, 0}, std::sqrt(0.75f)}, static_cast<float>(width) / height);
    Renderer renderer(2);
    Framebuffer target(width, height);
    renderer.clear(target);
    scene.render(renderer, target, view, SceneOptions{});
    renderer.finish(target);
    const std::vector<float> depth = linear_depth(target, view.clip_from_view);
    const CameraModel camera = camera_model(view, width, height);
    ASSERT_TRUE(camera.perspective);
    const glm::mat4 world_from_cv = glm::inverse(camera.camera_from_world_cv);
    int drawn = 0;
    for (int v = 0; v < height; ++v)
      for (int u = 0; u < width; ++u) {
        const float d = depth[static_cast<std::size_t>(v * width + u)];
        if (d == 0.0f) continue;
        ++drawn;
        const glm::vec3 cv((u - camera.K[2][0]) * d / camera.K[0][0], (v - camera.K[2][1]) * d / camera.K[1][1], d);
        const glm::vec3 world(world_from_cv * glm::vec4(cv, 1.0f));
        const float extent = std::max({std::abs(world.x), std::abs(world.y), std::abs(world.z)});
        EXPECT_NEAR(extent, 0.5f, 2e-3f) << "pixel " << u << "," << v;
      }
    EXPECT_GT(drawn, width * height / 10);
    // The OpenGL pose and the OpenCV one are the same camera with y and z flipped.
    const glm::mat4 gl_from_cv = glm::inverse(camera.world_from_camera) * world_from_cv;
    EXPECT_NEAR(gl_from_cv[1][1], -1.0f, 1e-5f);
    EXPECT_NEAR(gl_from_cv[2][2], -1.0f, 1e-5f);
  }
}

// Anti-aliased, the colour is a blend of samples but ids, depth and the mask are sample 0's: every id names a real
// triangle of the model (a blend of ids would not), and the three agree on every pixel.
TEST(Render, AntialiasedBuffersHoldSingleSamples) {
  const std::filesystem::path dir = test::scratch_dir("render_job");
  RenderJob job;
  job.model = kBox;
  job.width = 64;
  job.height = 48;
  job.samples = 8;
  job.outputs = {.color = dir / "aa.png", .depth = dir / "aa_depth.npy", .ids = dir / "aa_ids.npy",
                 .mask = dir / "aa_mask.png"};
  Renderer renderer(2);
  render(job, renderer);
  const test::Npy ids = test::read_npy(dir / "aa_ids.npy");
  const test::Npy depth = test::read_npy(dir / "aa_depth.npy");
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(dir / "aa_mask.png", w, h);
  ASSERT_EQ(ids.words.size(), 2u * static_cast<std::size_t>(w * h));
  ASSERT_EQ(depth.words.size(), static_cast<std::size_t>(w * h));
  int drawn = 0;
  for (std::size_t p = 0; p < static_cast<std::size_t>(w * h); ++p) {
    const std::uint32_t face = ids.words[2 * p + 1];
    const bool has_id = face != kNoSurface, has_depth = std::bit_cast<float>(depth.words[p]) > 0.0f;
    ASSERT_TRUE(!has_id || face < 12u) << "pixel " << p << ": face " << face << " of a 12-triangle box";
    ASSERT_EQ(has_id, has_depth) << "pixel " << p;
    ASSERT_EQ(has_id, mask[4 * p] == 255) << "pixel " << p;
    drawn += has_id;
  }
  EXPECT_GT(drawn, 200);
}

TEST(Render, MaskDepthCameraAndImageAgree) {
  const std::filesystem::path dir = test::scratch_dir("render_job");
  RenderJob job;
  job.model = kBox;
  job.width = 48;
  job.height = 40;
  job.look.background = glm::vec3(0.0f, 1.0f, 0.0f);
  job.outputs = {.color = dir / "c.png", .depth = dir / "d.npy", .mask = dir / "m.png", .camera = dir / "camera.json"};
  Renderer renderer(2);
  // One sample: the mask is 0 exactly where the image shows the background. Four: the mask is sample 0's, so an
  // edge pixel, a blend of surface and background, may be in or out, but the rest agrees.
  int drawn = 0;
  for (const int samples : {4, 1}) {
    job.samples = samples;
    render(job, renderer);
    int w = 0, h = 0;
    const std::vector<std::uint8_t> color = read_png(dir / "c.png", w, h);
    const std::vector<std::uint8_t> mask = read_png(dir / "m.png", w, h);
    ASSERT_EQ(w * h, 48 * 40);
    drawn = 0;
    int sample_0_empty = 0;  // pixels showing some of the box whose sample 0 misses it
    for (int i = 0; i < w * h; ++i) {
      const std::uint8_t m = mask[static_cast<std::size_t>(i) * 4];
      ASSERT_TRUE(m == 0 || m == 255);
      const bool background = color[i * 4] == 0 && color[i * 4 + 1] == 255 && color[i * 4 + 2] == 0;
      drawn += m == 255;
      if (background) EXPECT_EQ(m, 0) << "pixel " << i << ", " << samples << " samples";
      else if (m == 0) ++sample_0_empty;
    }
    if (samples == 1) EXPECT_EQ(sample_0_empty, 0);
    else EXPECT_LT(sample_0_empty, drawn / 8) << "only silhouette pixels";
  }
  EXPECT_GT(drawn, 100);
  std::ifstream json(dir / "camera.json");
  const std::string text((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  for (const char* key : {"\"width\": 48", "\"height\": 40", "\"projection\": \"perspective\"", "\"K\": [[",
                          "\"world_from_camera\"", "\"camera_from_world\""})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text;

  job.camera.projection = Projection::isometric;
  render(job, renderer);
  std::ifstream parallel(dir / "camera.json");
  const std::string iso((std::istreambuf_iterator<char>(parallel)), std::istreambuf_iterator<char>());
  EXPECT_NE(iso.find("\"projection\": \"parallel\",\n  \"K\": null"), std::string::npos) << iso;
}

}  // namespace
}  // namespace facet::render_job_tests
