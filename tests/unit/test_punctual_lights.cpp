// test_punctual_lights.cpp - lights a glTF file places (KHR_lights_punctual): read, checked, falling off, drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "facet/scene.hpp"
#include "facet/shaders/punctual.hpp"
#include "facet/warnings.hpp"
#include "support/gltf_square.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::punctual_lights_tests {
namespace {

namespace fs = std::filesystem;

// The square with light nodes after it; `lights` is the extension's array of lights.
std::string square_with_lights(const std::string& light_nodes, int count, const std::string& lights,
                               const std::string& material = "") {
  return test::square_gltf(light_nodes, count,
                           R"(,"extensionsUsed":["KHR_lights_punctual"],)"
                           R"("extensions":{"KHR_lights_punctual":{"lights":)" +
                               lights + "}}",
                           material);
}

std::string light_node(int light, const std::string& transform) {
  return R"({"extensions":{"KHR_lights_punctual":{"light":)" + std::to_string(light) + "}}" +
         (transform.empty() ? "" : "," + transform) + "}";
}

void expect_near(glm::vec3 a, glm::vec3 b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

// A render of `model` through its camera 0, size x size, 1 sample, with `look`, written to `png` and read back.
struct Picture {
  std::vector<std::uint8_t> rgba;
  int size = 0;
  int red(int x, int y) const { return rgba[(static_cast<std::size_t>(y) * size + x) * 4]; }
};

Picture render_look(const fs::path& model, int size, const LookSpec& look, const fs::path& png) {
  Renderer renderer(2);
  RenderJob job;
  job.model = model;
  job.width = job.height = size;
  job.samples = 1;
  job.camera.file_camera = 0;
  job.look = look;
  job.outputs = {.color = png};
  render(job, renderer);
  int w = 0, h = 0;
  return {read_png(png, w, h), size};
}

TEST(PunctualLights, ReadAsTheirNodesPlaceThem) {
  const fs::path dir = test::scratch_dir("punctual_lights");
  const std::string nodes = light_node(0, R"("rotation":[-0.70710678,0,0,0.70710678])") + "," +
                            light_node(1, R"("translation":[1,2,3])") + "," +
                            light_node(2, R"("translation":[0,0,2],"rotation":[0,1,0,0])") + "," + light_node(3, "");
  const fs::path model = test::write_file(
      dir, "lights.gltf",
      square_with_lights(nodes, 4,
                         R"([{"type":"directional","color":[1,0.5,0.25],"intensity":3,"name":"sun"},)"
                         R"({"type":"point","intensity":10,"range":5},)"
                         R"({"type":"spot","intensity":20,"spot":{"innerConeAngle":0.1,"outerConeAngle":0.3}},)"
                         R"({"type":"point","intensity":-1}])"));
  WarningCapture warnings;
  const Mesh mesh = load_model(model);
  ASSERT_EQ(mesh.lights.size(), 3u);
  const Light& sun = mesh.lights[0];
  EXPECT_EQ(sun.kind, Light::Kind::directional);
  EXPECT_EQ(sun.name, "sun");
  EXPECT_EQ(sun.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(sun.intensity, 3.0f);
  expect_near(sun.vector, glm::vec3(0.0f, 1.0f, 0.0f));  // shines down its node's -Z, turned to -Y
  const Light& point = mesh.lights[1];
  EXPECT_EQ(point.kind, Light::Kind::point);
  EXPECT_EQ(point.vector, glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(point.range, 5.0f);
  EXPECT_EQ(point.color, glm::vec3(1.0f));
  const Light& spot = mesh.lights[2];
  EXPECT_EQ(spot.kind, Light::Kind::spot);
  EXPECT_EQ(spot.vector, glm::vec3(0.0f, 0.0f, 2.0f));
  expect_near(spot.spot_direction, glm::vec3(0.0f, 0.0f, 1.0f));  // turned half round about +Y
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.1f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.3f);
  ASSERT_EQ(warnings.messages().size(), 1u);
  EXPECT_NE(warnings.messages()[0].find("light 3 has a negative or non-finite colour or intensity"), std::string::npos)
      << warnings.messages()[0];
}

TEST(PunctualLights, BadConesAreClampedAndMissingLightsRefused) {
  const fs::path dir = test::scratch_dir("punctual_lights");
  WarningCapture warnings;
  const Mesh mesh = load_model(test::write_file(
      dir, "cone.gltf",
      square_with_lights(light_node(0, ""), 1,
                         R"([{"type":"spot","spot":{"innerConeAngle":0.9,"outerConeAngle":2.5}}])")));
  ASSERT_EQ(mesh.lights.size(), 1u);
  EXPECT_LT(mesh.lights[0].inner_cone, mesh.lights[0].outer_cone);
  EXPECT_LE(mesh.lights[0].outer_cone, 1.5707964f);
  ASSERT_EQ(warnings.messages().size(), 1u);
  EXPECT_NE(warnings.messages()[0].find("clamped"), std::string::npos);

  const fs::path missing =
      test::write_file(dir, "missing.gltf", square_with_lights(light_node(9, ""), 1, R"([{"type":"point"}])"));
  EXPECT_EQ(test::load_problem(missing), "light 9 does not exist");
}

// Hostile light declarations: each is refused with a one-line error naming the file, or drawn without the light
// with a warning; none crashes or hangs.
TEST(PunctualLights, HostileDeclarationsAreRefusedOrLeftOut) {
  const fs::path dir = test::scratch_dir("punctual_lights");
  struct Case {
    const char* name;
    std::string node, lights;
    bool refused;
  };
  const Case cases[] = {
      {"negative index", light_node(-1, ""), R"([{"type":"point"}])", true},
      {"string index", R"({"extensions":{"KHR_lights_punctual":{"light":"0"}}})", R"([{"type":"point"}])", true},
      {"fractional index", R"({"extensions":{"KHR_lights_punctual":{"light":0.5}}})", R"([{"type":"point"}])", true},
      {"huge index", R"({"extensions":{"KHR_lights_punctual":{"light":1e300}}})", R"([{"type":"point"}])", true},
      {"two-channel colour", light_node(0, ""), R"([{"type":"point","color":[1,1]}])", false},
      {"unknown type", light_node(0, ""), R"([{"type":"area"}])", false},
      {"NaN-making scale", light_node(0, R"("scale":[0,0,0])"), R"([{"type":"directional"}])", false},
      {"huge intensity", light_node(0, ""), R"([{"type":"point","intensity":1e39}])", false},
  };
  for (const Case& c : cases) {
    const fs::path model = test::write_file(dir, "hostile.gltf", square_with_lights(c.node, 1, c.lights));
    WarningCapture warnings;
    if (c.refused) {
      EXPECT_FALSE(test::load_problem(model).empty()) << c.name;
      continue;
    }
    try {
      const Mesh mesh = load_model(model);
      EXPECT_TRUE(mesh.lights.empty()) << c.name;
    } catch (const InputError& e) {
      ADD_FAILURE() << c.name << ": refused: " << e.what();
    }
  }
}

// KHR_lights_punctual's recommended falloff: inverse square, windowed by the range, a spot's cone smoothly cut.
TEST(PunctualLights, FallOffAsTheExtensionRecommends) {
  Light point{Light::Kind::point, glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(1.0f), 4.0f};
  glm::vec3 l;
  float falloff = 0.0f;
  incident_light(PunctualLight::from(point), glm::vec3(0.0f), l, falloff);
  EXPECT_EQ(l, glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_FLOAT_EQ(falloff, 0.25f);
  point.range = 4.0f;  // d = range / 2
  incident_light(PunctualLight::from(point), glm::vec3(0.0f), l, falloff);
  EXPECT_FLOAT_EQ(falloff, (1.0f - 1.0f / 16.0f) / 4.0f);
  incident_light(PunctualLight::from(point), glm::vec3(0.0f, 0.0f, -3.0f), l, falloff);
  EXPECT_EQ(falloff, 0.0f);  // beyond the range

  Light spot{Light::Kind::spot, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(1.0f), 1.0f};
  spot.spot_direction = glm::vec3(0.0f, 0.0f, -1.0f);
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.4f;
  const PunctualLight s = PunctualLight::from(spot);
  const auto at_angle = [&](float angle) {
    const glm::vec3 p(std::tan(angle), 0.0f, 0.0f);
    incident_light(s, p, l, falloff);
    return falloff * glm::dot(spot.vector - p, spot.vector - p);  // the distance's share taken out
  };
  EXPECT_NEAR(at_angle(0.0f), 1.0f, 1e-5f);
  EXPECT_NEAR(at_angle(0.19f), 1.0f, 1e-5f);
  EXPECT_EQ(at_angle(0.41f), 0.0f);
  const float mid = (std::cos(0.3f) - std::cos(0.4f)) / (std::cos(0.2f) - std::cos(0.4f));
  EXPECT_NEAR(at_angle(0.3f), mid * mid, 1e-4f);

  Light sun;
  sun.vector = glm::vec3(0.0f, 3.0f, 4.0f);
  incident_light(PunctualLight::from(sun), glm::vec3(7.0f), l, falloff);
  expect_near(l, glm::vec3(0.0f, 0.6f, 0.8f));
  EXPECT_EQ(falloff, 1.0f);
}

// A spot above the square's middle lights a disc there and nothing outside its cone; --no-model-lights drops it.
TEST(PunctualLights, ASpotLightsItsConeInTheModelsOwnLook) {
  const fs::path dir = test::scratch_dir("punctual_lights");
  const std::string camera = R"({"camera":0,"translation":[0,0,5]})";
  const fs::path model = test::write_file(
      dir, "spot.gltf",
      test::square_gltf(camera + "," + light_node(0, R"("translation":[0,0,2])"), 2,
                        R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.7610127,"znear":0.1}}],)"
                        R"("extensions":{"KHR_lights_punctual":{"lights":)"
                        R"([{"type":"spot","intensity":8,"spot":{"innerConeAngle":0.2,"outerConeAngle":0.3}}]}})",
                        R"({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":0.8}})"));
  LookSpec look;
  const Picture lit = render_look(model, 64, look, dir / "lit.png");
  look.model_lights = false;
  const Picture unlit = render_look(model, 64, look, dir / "unlit.png");
  // The square spans pixels 16..47; its middle lies in the cone, (18, 18) well outside it.
  EXPECT_GT(lit.red(32, 32), unlit.red(32, 32) + 60);
  EXPECT_EQ(lit.red(18, 18), unlit.red(18, 18));
}

// A small square held above the floor square, a directional light from 45 degrees: with shadows, the floor darkens
// where the small square hides the light and nowhere else.
TEST(PunctualLights, DirectionalLightsCastShadowsWhenAsked) {
  const fs::path dir = test::scratch_dir("punctual_lights");
  const std::string nodes = R"({"camera":0,"translation":[0,0,5]},)"
                            R"({"mesh":0,"translation":[0,0,0.5],"scale":[0.3,0.3,1]},)" +
                            light_node(0, R"("rotation":[0,0.3826834,0,0.9238795])");
  const fs::path model = test::write_file(
      dir, "shadow.gltf",
      test::square_gltf(nodes, 3,
                        R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.7610127,"znear":0.1}}],)"
                        R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"directional","intensity":3}]}})",
                        R"({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":0.8},"doubleSided":true})"));
  LookSpec look;
  const Picture unshadowed = render_look(model, 64, look, dir / "unshadowed.png");
  look.shadows = true;
  const Picture shadowed = render_look(model, 64, look, dir / "shadowed.png");
  // 16 pixels a unit on the floor: the shadow falls on x in [-0.8, -0.2], the occluder hides x in [-0.33, 0.33].
  EXPECT_LT(shadowed.red(22, 32) + 40, unshadowed.red(22, 32));  // x = -0.6: in the shadow
  EXPECT_EQ(shadowed.red(42, 32), unshadowed.red(42, 32));       // x = +0.6: lit either way
  EXPECT_EQ(shadowed.red(32, 32), unshadowed.red(32, 32));       // the occluder itself is lit
}

// Shadows asked of a look with no light that casts them say so; an absurd map size is refused before drawing.
TEST(PunctualLights, ShadowsWithoutACasterWarnAndBadMapSizesAreRefused) {
  LookSpec look;
  look.shadows = true;
  {
    WarningCapture warnings;
    const SceneOptions options = scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f));
    EXPECT_TRUE(options.shadows);
    ASSERT_EQ(warnings.messages().size(), 1u);
    EXPECT_NE(warnings.messages()[0].find("no directional or spot light"), std::string::npos);
  }
  look.light_direction = glm::vec3(0.0f, 1.0f, 0.0f);
  WarningCapture warnings;
  SceneOptions options = scene_options(look, glm::mat4(1.0f), Shading::automatic, glm::vec3(0.0f));
  EXPECT_TRUE(warnings.messages().empty());
  Scene scene;
  scene.add(Instance{std::make_shared<const Mesh>(load_model("/usr/share/assimp/models/OBJ/box.obj"))});
  Renderer renderer(1);
  Framebuffer target(16, 16);
  const View view{glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -5.0f)),
                  glm::perspective(0.8f, 1.0f, 0.1f, 20.0f)};
  for (const int size : {0, -3, 8193}) {
    options.shadow_map_size = size;
    EXPECT_THROW(scene.render(renderer, target, view, options), std::invalid_argument) << size;
  }
  options.shadow_map_size = 64;
  EXPECT_EQ(scene.render(renderer, target, view, options), 1u);
}

// A small square just above the floor square: ambient occlusion darkens the floor beside it, where the small
// square hides part of the sky, and leaves the open floor farther off and the small square's top as they were.
TEST(AmbientOcclusion, DarkensTheFloorBesideWhatStandsOnIt) {
  const fs::path dir = test::scratch_dir("ambient_occlusion");
  const std::string nodes = R"({"camera":0,"translation":[0,0,5]},)"
                            R"({"mesh":0,"translation":[0,0,0.1],"scale":[0.3,0.3,1]})";
  const fs::path model = test::write_file(
      dir, "contact.gltf",
      test::square_gltf(nodes, 2, R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.7610127,"znear":0.1}}])",
                        R"({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":0.8},"doubleSided":true})"));
  LookSpec look;
  const Picture open = render_look(model, 128, look, dir / "open.png");
  look.ambient_occlusion = true;
  const Picture occluded = render_look(model, 128, look, dir / "occluded.png");
  // 32 pixels a unit on the floor; the small square covers x in [-0.3, 0.3].
  EXPECT_LT(occluded.red(76, 64) + 15, open.red(76, 64));  // x = 0.4: beside it
  EXPECT_EQ(occluded.red(94, 64), open.red(94, 64));       // x = 0.95: open floor
  EXPECT_EQ(occluded.red(64, 64), open.red(64, 64));       // its top
}

}  // namespace
}  // namespace facet::punctual_lights_tests
