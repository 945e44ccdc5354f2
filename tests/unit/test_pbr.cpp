// test_pbr.cpp - the metallic-roughness BRDF against numerical integrals, the environment's prefiltering, tone
// mapping and the colour spaces of glTF's factors.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <array>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "facet/color.hpp"
#include "facet/environment.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/pbr.hpp"
#include "facet/texture.hpp"
#include "facet/view_spec.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::pbr_tests {
namespace {

namespace fs = std::filesystem;
constexpr float kPi = brdf::kPi;

EnvironmentImage uniform_image(glm::vec3 radiance, int width = 64, int height = 32) {
  EnvironmentImage image;
  image.width = width;
  image.height = height;
  image.texels.assign(static_cast<std::size_t>(width * height), radiance);
  return image;
}

// f(l, v) for unit vectors around n = (0, 0, 1): reflect_light divided by NdotL.
brdf::Rgb<float> brdf_value(const brdf::Surface<float>& s, glm::vec3 l, glm::vec3 v) {
  const glm::vec3 h = glm::normalize(l + v);
  const float n_dot_l = l.z, n_dot_v = v.z;
  const brdf::Rgb<float> r = brdf::reflect_light(s, n_dot_l, n_dot_v, h.z, glm::dot(v, h));
  return {r.r / n_dot_l, r.g / n_dot_l, r.b / n_dot_l};
}

glm::vec3 direction(float cos_theta, float phi) {
  const float sin_theta = std::sqrt(1.0f - cos_theta * cos_theta);
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

// Helmholtz reciprocity: f(l, v) = f(v, l), for metals and dielectrics at any roughness.
TEST(Brdf, IsReciprocal) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> unit(0.05f, 1.0f), angle(0.0f, 6.2831853f);
  for (int i = 0; i < 200; ++i) {
    const brdf::Surface<float> s =
        brdf::surface(brdf::Rgb<float>{unit(rng), unit(rng), unit(rng)}, unit(rng) - 0.05f, unit(rng));
    const glm::vec3 l = direction(unit(rng), angle(rng)), v = direction(unit(rng), angle(rng));
    const brdf::Rgb<float> a = brdf_value(s, l, v), b = brdf_value(s, v, l);
    EXPECT_NEAR(a.r, b.r, 1e-4f * (1.0f + a.r));
    EXPECT_NEAR(a.g, b.g, 1e-4f * (1.0f + a.g));
    EXPECT_NEAR(a.b, b.b, 1e-4f * (1.0f + a.b));
  }
}

// The directional albedo of a white metal (F = 1), integrated over the hemisphere with many stratified directions,
// is what the split-sum table holds (A + B), and never more than 1: the specular lobe creates no energy.
TEST(Brdf, AlbedoMatchesTheSplitSumTableAndConservesEnergy) {
  const brdf::Surface<float> metal = brdf::surface(brdf::Rgb<float>{1.0f, 1.0f, 1.0f}, 1.0f, 0.0f);
  for (const float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    brdf::Surface<float> s = metal;
    s.roughness = roughness;
    s.alpha = roughness * roughness;
    for (const float n_dot_v : {0.2f, 0.5f, 0.9f}) {
      const glm::vec3 v = direction(n_dot_v, 0.0f);
      constexpr int kTheta = 400, kPhi = 400;
      double albedo = 0.0;
      for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
          // Uniform in cos(theta): each cell has solid angle 2 pi / (kTheta kPhi).
          const float cos_theta = (static_cast<float>(i) + 0.5f) / kTheta;
          const glm::vec3 l = direction(cos_theta, 6.2831853f * (static_cast<float>(j) + 0.5f) / kPhi);
          albedo += brdf_value(s, l, v).r * cos_theta;
        }
      albedo *= 2.0 * kPi / (kTheta * kPhi);
      const glm::vec2 ab = brdf_table(n_dot_v, roughness);
      EXPECT_LE(albedo, 1.0) << "roughness " << roughness << ", NdotV " << n_dot_v;
      EXPECT_NEAR(ab.x + ab.y, albedo, 0.03) << "roughness " << roughness << ", NdotV " << n_dot_v;
    }
  }
}

// A uniform environment's irradiance is pi times its radiance everywhere, and its prefiltered radiance is itself.
TEST(Environment, UniformLightIsPrefilteredToItself) {
  const Environment env(uniform_image(glm::vec3(0.5f, 1.0f, 2.0f)));
  std::mt19937 rng(2);
  std::normal_distribution<float> gauss;
  for (int i = 0; i < 50; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
    const glm::vec3 e = env.irradiance(d);
    EXPECT_NEAR(e.r, 0.5f * kPi, 0.01f);
    EXPECT_NEAR(e.b, 2.0f * kPi, 0.04f);
    for (const float roughness : {0.0f, 0.3f, 1.0f}) {
      const glm::vec3 l = env.radiance(d, roughness);
      EXPECT_NEAR(l.g, 1.0f, 1e-3f) << roughness;
    }
  }
}

// A sky (radiance 1 above the horizon, 0 below) gives a surface facing up pi, one facing down nothing and a wall
// half: the harmonics' cosine convolution, within the few per cent degree 2 can hold.
TEST(Environment, SkyIrradianceFollowsTheCosineLaw) {
  EnvironmentImage sky = uniform_image(glm::vec3(0.0f), 128, 64);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 128; ++x) sky.texels[static_cast<std::size_t>(y * 128 + x)] = glm::vec3(1.0f);
  const Environment env(sky);
  EXPECT_NEAR(env.irradiance({0, 1, 0}).r, kPi, 0.1f * kPi);
  EXPECT_NEAR(env.irradiance({0, -1, 0}).r, 0.0f, 0.1f * kPi);
  EXPECT_NEAR(env.irradiance({1, 0, 0}).r, 0.5f * kPi, 0.03f * kPi);
  EXPECT_NEAR(env.irradiance({0, 0, -1}).r, 0.5f * kPi, 0.03f * kPi);
}

// three.js's orientation: the image's centre column faces +X, the column a quarter to its right +Z, the top row
// +Y; turning the environment by +90 degrees (counter-clockwise seen from above) moves what faced +X to -Z.
TEST(Environment, OrientationIsThreeJs) {
  const int w = 64, h = 32;
  EnvironmentImage image = uniform_image(glm::vec3(0.0f), w, h);
  const auto light = [&](int x, int y, glm::vec3 c) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) image.texels[static_cast<std::size_t>((y + dy) * w + x + dx)] = c;
  };
  light(w / 2, h / 2, {1, 0, 0});      // centre column, at the horizon
  light(3 * w / 4, h / 2, {0, 1, 0});  // a quarter to its right
  light(w / 2, 1, {0, 0, 1});          // near the top row
  const Environment env(image);
  EXPECT_GT(env.radiance({1, 0, 0}, 0.0f).r, 0.5f);
  EXPECT_LT(env.radiance({-1, 0, 0}, 0.0f).r, 0.01f);
  EXPECT_GT(env.radiance({0, 0, 1}, 0.0f).g, 0.5f);
  EXPECT_GT(env.radiance(glm::normalize(glm::vec3(1, 15, 0)), 0.0f).b, 0.5f);
  const Environment turned(image, 90.0f);
  EXPECT_GT(turned.radiance({0, 0, -1}, 0.0f).r, 0.5f);
  EXPECT_LT(turned.radiance({1, 0, 0}, 0.0f).r, 0.01f);
}

// The white furnace: a white surface lit by a uniform white environment reflects it evenly, whatever the view
// angle, roughness or metalness (with the multiple-scattering term; within a few per cent where the split-sum
// table's resolution shows). Tone mapping off, so the radiance itself is compared.
TEST(PbrShader, WhiteFurnaceReflectsTheEnvironmentEvenly) {
  const Environment env(uniform_image(glm::vec3(1.0f)));
  PbrShader shader;
  shader.environment = &env;
  shader.eye = glm::vec3(0.0f, 0.0f, 1.0f);
  for (const float metallic : {0.0f, 1.0f})
    for (const float roughness : {0.2f, 0.6f, 1.0f})
      for (const float n_dot_v : {0.3f, 0.7f, 1.0f}) {
        PbrMaterial m;
        m.metallic = metallic;
        m.roughness = roughness;
        const PbrInputs<float> in = factor_inputs<float>(m, {1.0f, 1.0f, 1.0f}, 1.0f);
        const glm::vec3 n = direction(n_dot_v, 0.0f);
        const brdf::Rgb<float> c = shader.shade(in, n, n, glm::vec3(0.0f));
        EXPECT_NEAR(c.r, 1.0f, 0.06f) << "metallic " << metallic << ", roughness " << roughness << ", NdotV "
                                      << n_dot_v;
      }
}

// Emission adds to the reflected light before tone mapping; a black, non-reflecting surface shows it alone.
TEST(PbrShader, EmissionIsAddedInLinearLight) {
  PbrShader shader;
  shader.eye = glm::vec3(0.0f, 0.0f, 1.0f);
  shader.tone_mapping = ToneMapping::none;
  PbrMaterial m;
  m.roughness = 1.0f;
  m.emissive = glm::vec3(0.25f, 0.5f, 0.0f);
  const PbrInputs<float> in = factor_inputs<float>(m, {0.0f, 0.0f, 0.0f}, 1.0f);
  const brdf::Rgb<float> c = shader.display(
      shader.shade(in, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0.0f)));
  EXPECT_NEAR(c.r, linear_to_srgb(0.25f), 2e-4f);
  EXPECT_NEAR(c.g, linear_to_srgb(0.5f), 2e-4f);
  EXPECT_NEAR(c.b, 0.0f, 2e-4f);
}

// Without an environment a white metal (glTF's default material) is still lit by a light: no 0 / 0 in the
// multiple-scattering term, whose table terms are then zero.
TEST(PbrShader, AWhiteMetalWithoutEnvironmentIsLit) {
  PbrShader shader;
  shader.eye = glm::vec3(0.0f, 0.0f, 1.0f);
  shader.ambient = glm::vec3(0.1f);
  const PunctualLight light = PunctualLight::from(Light{Light::Kind::directional, glm::vec3(0.0f, 0.3f, 1.0f)});
  shader.lights = std::span<const PunctualLight>(&light, 1);
  PbrMaterial m;
  m.metallic = 1.0f;
  m.roughness = 1.0f;
  const PbrInputs<float> in = factor_inputs<float>(m, {1.0f, 1.0f, 1.0f}, 1.0f);
  const brdf::Rgb<float> c = shader.shade(in, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0.0f));
  EXPECT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
  EXPECT_GT(c.r, 0.05f);
}

// A Z-up model's environment has its up turned to +Z: what the upright studio sends down from +Y, the turned one
// sends down from +Z, and render jobs turn it by the camera's up axis.
TEST(Environment, TurnsItsUpToTheModelsUpAxis) {
  const EnvironmentImage image = studio_environment();
  const Environment upright(image);
  const Environment z_up(image, 0.0f, 1.0f, glm::transpose(upright_from_model(UpAxis::pos_z)));
  for (const glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::vec3(0.3f, 0.8f, -0.5f)}) {
    const glm::vec3 turned = glm::transpose(upright_from_model(UpAxis::pos_z)) * n;
    const std::array<float, 3> a = upright.irradiance(n.x, n.y, n.z), b = z_up.irradiance(turned.x, turned.y, turned.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c], a[c], 1e-3f * (1.0f + a[c])) << n.x << " " << n.y << " " << n.z;
  }
  // The studio's dome (above) is brighter than its floor (below): up is +Z once turned.
  EXPECT_GT(z_up.irradiance(0, 0, 1)[1], 1.5f * z_up.irradiance(0, 0, -1)[1]);
  EXPECT_NE(environment_for(LookSpec{}, UpAxis::pos_z), environment_for(LookSpec{}, UpAxis::pos_y));
}

// Khronos PBR Neutral leaves dark colours nearly as they are, keeps greys grey and brings any light into [0, 1];
// ACES too. Both rise with the light.
TEST(ToneMapping, NeutralAndAcesStayInRangeAndRise) {
  float previous_neutral = -1.0f, previous_aces = -1.0f;
  for (float x = 0.0f; x < 1000.0f; x = x * 1.5f + 0.01f) {
    const brdf::Rgb<float> n = brdf::tone_map(brdf::Rgb<float>{x, x, x}, ToneMapping::neutral, 1.0f);
    const brdf::Rgb<float> a = brdf::tone_map(brdf::Rgb<float>{x, x, x}, ToneMapping::aces, 1.0f);
    EXPECT_GE(n.r, previous_neutral);
    EXPECT_LE(n.r, 1.0f);
    EXPECT_FLOAT_EQ(n.r, n.g);
    EXPECT_GE(a.r, previous_aces - 1e-6f);
    EXPECT_LE(a.r, 1.0f);
    previous_neutral = n.r, previous_aces = a.r;
  }
  // Below 0.76 Neutral only lifts the black point offset: 0.5 grey comes out 0.46.
  EXPECT_NEAR(brdf::tone_map(brdf::Rgb<float>{0.5f, 0.5f, 0.5f}, ToneMapping::neutral, 1.0f).r, 0.46f, 1e-6f);
  EXPECT_NEAR(brdf::tone_map(brdf::Rgb<float>{0.25f, 0.25f, 0.25f}, ToneMapping::neutral, 2.0f).r, 0.46f, 1e-6f);
}

// glTF's baseColorFactor and COLOR_0 are linear: 0.604 is displayed as sRGB 204 (0.8), and an unlit material shows
// exactly that.
TEST(GltfColorSpace, FactorsAreLinear) {
  const fs::path dir = test::scratch_dir("pbr_color_space");
  const fs::path model = test::write_file(
      dir, "grey.gltf",
      R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_materials_unlit"],"buffers":[{"byteLength":36,)"
      R"("uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,)"
      R"("type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"materials":[{"pbrMetallicRoughness":{"baseColorFactor":)"
      R"([0.604,0.604,0.604,1]},"extensions":{"KHR_materials_unlit":{}}}],"meshes":[{"primitives":[{"attributes":)"
      R"({"POSITION":0},"material":0}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
  const Mesh mesh = load_model(model);
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_NEAR(mesh.materials[0].diffuse.r * 255.0f, 204.0f, 0.5f);
}

// A glTF primitive without a material gets the specification's default: white, fully metallic, fully rough.
TEST(GltfColorSpace, MissingMaterialIsTheSpecificationsDefault) {
  const fs::path dir = test::scratch_dir("pbr_color_space");
  const fs::path model = test::write_file(
      dir, "bare.gltf",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,)"
      R"("uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,)"
      R"("type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
      R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
  const Mesh mesh = load_model(model);
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].diffuse, glm::vec4(1.0f));
  EXPECT_EQ(mesh.materials[0].metallic, 1.0f);
  EXPECT_EQ(mesh.materials[0].roughness, 1.0f);
  EXPECT_FALSE(mesh.materials[0].double_sided);
}

// --hdri-background: each pixel shows the environment along its view ray, perspective or parallel, tone-mapped
// like the model. An environment red towards +X, green towards +Z, blue elsewhere, seen from the origin.
TEST(EnvironmentBackground, ShowsTheEnvironmentAlongEachRay) {
  EnvironmentImage image = uniform_image(glm::vec3(0.0f, 0.0f, 1.0f), 64, 32);
  for (int y = 8; y < 24; ++y)
    for (int x = 0; x < 64; ++x) {
      if (x >= 24 && x < 40) image.texels[static_cast<std::size_t>(y * 64 + x)] = glm::vec3(1.0f, 0.0f, 0.0f);
      if (x >= 40 && x < 56) image.texels[static_cast<std::size_t>(y * 64 + x)] = glm::vec3(0.0f, 1.0f, 0.0f);
    }
  SceneOptions options;
  options.environment = std::make_shared<const Environment>(image);
  options.environment_background = true;
  options.tone_mapping = ToneMapping::none;
  Scene scene;
  Renderer renderer(2);
  for (const bool parallel : {false, true})
    for (const auto& [target, channel] : {std::pair{glm::vec3(1, 0, 0), 0}, std::pair{glm::vec3(0, 0, 1), 1}}) {
      View view;
      view.view_from_world = glm::lookAt(glm::vec3(0.0f), target, glm::vec3(0, 1, 0));
      view.clip_from_view = parallel ? glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f)
                                     : glm::perspective(0.5f, 1.0f, 0.1f, 10.0f);
      Framebuffer fb(32, 32);
      renderer.clear(fb, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      scene.render(renderer, fb, view, options);
      renderer.finish(fb);
      const std::uint32_t centre = fb.pixel(16, 16);
      EXPECT_EQ((centre >> (8 * channel)) & 0xffu, 255u) << "towards " << target.x << "," << target.z;
      EXPECT_EQ((centre >> 16) & 0xffu, 0u) << "no blue towards " << target.x << "," << target.z;
    }
}

// sample_linear gives an sRGB texture's filtered colour in linear light: what sample() gives, decoded (to the
// encoding table's precision), for every filter; a linear texture's exactly as sample() gives it.
TEST(TextureLinear, IsTheDecodedSample) {
  std::mt19937 rng(8);
  std::vector<std::uint32_t> texels(16 * 8);
  for (std::uint32_t& t : texels) t = static_cast<std::uint32_t>(rng());
  Texture srgb(16, 8, texels, TexelEncoding::srgb), linear(16, 8, texels);
  srgb.generate_mipmaps();
  linear.generate_mipmaps();
  std::uniform_real_distribution<float> unit(-1.0f, 2.0f), step(0.0f, 0.3f);
  for (const Filter filter : {Filter::nearest, Filter::bilinear, Filter::trilinear})
    for (int i = 0; i < 200; ++i) {
      const Sampler sampler{filter, Wrap::repeat, Wrap::mirror};
      const glm::vec2 uv(unit(rng), unit(rng)), dx(step(rng), 0.0f), dy(0.0f, step(rng));
      const glm::vec4 encoded = srgb.sample(uv, dx, dy, sampler), decoded = srgb.sample_linear(uv, dx, dy, sampler);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(decoded[c], srgb_to_linear(encoded[c]), 2e-4f) << c;
      EXPECT_FLOAT_EQ(decoded.a, encoded.a);
      EXPECT_EQ(linear.sample_linear(uv, dx, dy, sampler), linear.sample(uv, dx, dy, sampler));
    }
}

}  // namespace
}  // namespace facet::pbr_tests
