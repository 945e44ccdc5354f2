// test_clearcoat_sheen.cpp - KHR_materials_clearcoat, _sheen and _transmission: the layers' formulas, how they
// light a surface, and what the glTF reader keeps of them (values the specification does not allow included).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/environment.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/shaders/brdf_layers.hpp"
#include "facet/shaders/pbr.hpp"
#include "facet/warnings.hpp"
#include "support/gltf_square.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::clearcoat_sheen_tests {
namespace {

namespace fs = std::filesystem;
constexpr float kPi = brdf::kPi;

// exp2 and log2 of exact operations agree with the C library's to a few parts in a million, and their lane
// versions with them bit for bit.
TEST(BrdfLayers, Exp2AndLog2AreAccurateAndAgreeInLanes) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f), mantissa(-20.0f, 20.0f);
  simd::Float xs, ys;
  for (int i = 0; i < 2000; ++i) {
    const float x = exponent(rng);
    EXPECT_NEAR(brdf::exp2(x) / std::exp2(x), 1.0f, 3e-6f) << x;
    const float y = std::exp2(mantissa(rng));
    EXPECT_NEAR(brdf::log2(y), std::log2(y), 4e-6f) << y;
    xs[i % simd::kLanes] = x, ys[i % simd::kLanes] = y;
    if (i % simd::kLanes != simd::kLanes - 1) continue;
    const simd::Float e = brdf::exp2(xs), l = brdf::log2(ys);
    for (int k = 0; k < simd::kLanes; ++k) {
      EXPECT_EQ(e[k], brdf::exp2(xs[k]));
      EXPECT_EQ(l[k], brdf::log2(ys[k]));
    }
  }
  // Past a float's normal range 2^x is clamped rather than turned into garbage bits.
  EXPECT_EQ(brdf::exp2(-1000.0f), std::exp2(-126.0f));
  EXPECT_TRUE(std::isfinite(brdf::exp2(1000.0f)));
}

// Sums f(h) (NdotH) over the hemisphere of half vectors, by the midpoint rule in theta and phi.
template <class Distribution>
double hemisphere_integral(const Distribution& d) {
  constexpr int kSteps = 2000;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double theta = (i + 0.5) * (kPi / 2.0) / kSteps;
    sum += d(static_cast<float>(std::cos(theta))) * std::cos(theta) * std::sin(theta);
  }
  return sum * (kPi / 2.0) / kSteps * 2.0 * kPi;
}

// The Charlie distribution is a distribution of microfacet normals: its projected area is 1 at every roughness.
TEST(BrdfLayers, CharlieDistributionIsNormalized) {
  for (const float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    const float alpha = roughness * roughness;
    const double area = hemisphere_integral([&](float n_dot_h) { return brdf::distribution_charlie(n_dot_h, alpha); });
    EXPECT_NEAR(area, 1.0, 0.01) << "roughness " << roughness;
  }
}

// The coat's Fresnel term is 0.04 head-on and rises to 1 at grazing angles; a coat lets the rest through.
TEST(BrdfLayers, CoatTransmittanceFollowsItsFresnelTerm) {
  EXPECT_FLOAT_EQ(brdf::coat_transmittance(1.0f, 1.0f), 0.96f);
  EXPECT_FLOAT_EQ(brdf::coat_transmittance(0.5f, 1.0f), 0.98f);
  EXPECT_NEAR(brdf::coat_transmittance(1.0f, 0.0f), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(brdf::coat_transmittance(0.0f, 0.2f), 1.0f);
}

EnvironmentImage white_image() {
  EnvironmentImage image;
  image.width = 64;
  image.height = 32;
  image.texels.assign(64 * 32, glm::vec3(1.0f));
  return image;
}

glm::vec3 direction(float cos_theta) { return {std::sqrt(1.0f - cos_theta * cos_theta), 0.0f, cos_theta}; }

// The white furnace with the layers on: a white rough dielectric under a coat or a white sheen still reflects a
// uniform white environment evenly (each layer takes from the layers below what it reflects itself).
TEST(PbrLayers, WhiteFurnaceHoldsWithCoatAndSheen) {
  const Environment env(white_image());
  PbrShader shader;
  shader.environment = &env;
  shader.eye = glm::vec3(0.0f, 0.0f, 1.0f);
  for (const int layer : {0, 1, 2})
    for (const float n_dot_v : {0.3f, 0.7f, 1.0f}) {
      shader.material = PbrMaterial{};
      shader.material.roughness = 0.8f;
      if (layer == 1) shader.material.clearcoat = 1.0f, shader.material.clearcoat_roughness = 0.1f;
      if (layer == 2) shader.material.sheen_color = glm::vec3(1.0f), shader.material.sheen_roughness = 0.5f;
      const PbrInputs<float> in = factor_inputs<float>(shader.material, {1.0f, 1.0f, 1.0f}, 1.0f);
      const glm::vec3 n = direction(n_dot_v);
      const brdf::Rgb<float> c = shader.shade(in, n, n, glm::vec3(0.0f));
      EXPECT_NEAR(c.r, 1.0f, 0.06f) << "layer " << layer << ", NdotV " << n_dot_v;
    }
}

// Radiance of a black rough dielectric, n = +z, under one white light from `light`, seen from `eye`.
float lit(const PbrMaterial& material, glm::vec3 light, glm::vec3 eye) {
  PbrShader shader;
  shader.material = material;
  const PunctualLight l = PunctualLight::from({Light::Kind::directional, light, glm::vec3(1.0f), kPi});
  shader.lights = std::span<const PunctualLight>(&l, 1);
  shader.eye = eye;
  const PbrInputs<float> in = factor_inputs<float>(material, {0.0f, 0.0f, 0.0f}, 1.0f);
  return shader.shade(in, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0.0f)).g;
}

// A glossy coat puts a sharp highlight on a rough surface; a sheen brightens it at grazing views most.
TEST(PbrLayers, CoatAddsAHighlightAndSheenARim) {
  PbrMaterial rough;
  rough.roughness = 1.0f;
  PbrMaterial coated = rough;
  coated.clearcoat = 1.0f;
  coated.clearcoat_roughness = 0.05f;
  const glm::vec3 light(0.3f, 0.0f, 1.0f), mirror(-0.3f, 0.0f, 1.0f), off_mirror(0.3f, 0.5f, 1.0f);
  EXPECT_GT(lit(coated, light, mirror), 20.0f * lit(rough, light, mirror));
  EXPECT_NEAR(lit(coated, light, off_mirror), lit(rough, light, off_mirror) * 0.96f, 0.02f);
  PbrMaterial sheened = rough;
  sheened.sheen_color = glm::vec3(1.0f);
  sheened.sheen_roughness = 0.5f;
  const glm::vec3 above(0.0f, 0.0f, 1.0f), grazing = direction(0.15f);
  const float rim = lit(sheened, above, grazing) - lit(rough, above, grazing);
  const float centre = lit(sheened, above, above) - lit(rough, above, above);
  EXPECT_GT(rim, 0.0f);
  EXPECT_GT(rim, 2.0f * centre);
}

// Transmission: a clear dielectric lets through all but its Fresnel reflection, so its coverage (alpha) is the
// reflectance at the view angle, 0.04 head-on rising towards 1 at grazing views; a metal transmits nothing.
TEST(PbrLayers, TransmissionCoversByTheFresnelTerm) {
  PbrShader shader;
  shader.eye = glm::vec3(0.0f, 0.0f, 1.0f);
  const auto coverage = [&](float metallic, float transmission, float n_dot_v) {
    shader.material = PbrMaterial{};
    shader.material.metallic = metallic;
    shader.material.roughness = 0.2f;
    shader.material.transmission = transmission;
    Fragment<PbrShader::Varyings> f{};
    f.varyings.normal = direction(n_dot_v);
    f.varyings.color = glm::vec4(1.0f);
    return shader.fragment(f).a;
  };
  EXPECT_NEAR(coverage(0.0f, 1.0f, 1.0f), 0.04f, 1e-4f);
  EXPECT_NEAR(coverage(0.0f, 1.0f, 0.1f), 0.04f + 0.96f * std::pow(0.9f, 5.0f), 1e-3f);
  EXPECT_NEAR(coverage(0.0f, 0.5f, 1.0f), 0.52f, 1e-4f);  // 1 - 0.5 (1 - 0.04)
  EXPECT_FLOAT_EQ(coverage(0.0f, 0.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(coverage(1.0f, 1.0f, 1.0f), 1.0f);
}

// The square with one material whose extensions are `extensions`; textures from a 2 x 2 PNG beside the file.
Mesh load_square(const std::string& name, const std::string& extensions) {
  const fs::path dir = test::scratch_dir("clearcoat_sheen");
  const std::vector<std::uint8_t> rgba = {255, 0, 0, 128, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0};
  write_png(dir / "layer.png", 2, 2, rgba);
  const std::string material = R"({"name":")" + name + R"(","extensions":{)" + extensions + "}}";
  const std::string images = R"(,"images":[{"uri":"layer.png"}],"textures":[{"source":0}])";
  return load_model(test::write_file(dir, name + ".gltf", test::square_gltf("", 0, images, material)));
}

TEST(GltfLayers, ReadsClearcoatAndSheen) {
  WarningCapture warnings;
  const Mesh mesh = load_square(
      "both", R"("KHR_materials_clearcoat":{"clearcoatFactor":0.75,"clearcoatTexture":{"index":0},)"
              R"("clearcoatRoughnessFactor":0.25,"clearcoatRoughnessTexture":{"index":0},)"
              R"("clearcoatNormalTexture":{"index":0,"scale":0.5}},)"
              R"("KHR_materials_sheen":{"sheenColorFactor":[1,0.5,0.25],"sheenColorTexture":{"index":0},)"
              R"("sheenRoughnessFactor":0.6,"sheenRoughnessTexture":{"index":0}})");
  EXPECT_TRUE(warnings.messages().empty()) << warnings.messages()[0];
  ASSERT_EQ(mesh.materials.size(), 1u);
  const Material& m = mesh.materials[0];
  EXPECT_FLOAT_EQ(m.clearcoat, 0.75f);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.25f);
  EXPECT_FLOAT_EQ(m.clearcoat_normal_scale, 0.5f);
  ASSERT_TRUE(m.clearcoat_map && m.clearcoat_roughness_map && m.clearcoat_normal_map);
  EXPECT_EQ(m.clearcoat_map->encoding(), TexelEncoding::linear);
  EXPECT_EQ(m.sheen_color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(m.sheen_roughness, 0.6f);
  ASSERT_TRUE(m.sheen_color_map && m.sheen_roughness_map);
  EXPECT_EQ(m.sheen_color_map->encoding(), TexelEncoding::srgb);
  EXPECT_EQ(m.sheen_roughness_map->encoding(), TexelEncoding::linear);
}

// A transmissive material is blended over what is behind it, unless the file masks it.
TEST(GltfLayers, TransmissionIsReadAndBlended) {
  WarningCapture warnings;
  const Mesh glass = load_square("glass", R"("KHR_materials_transmission":{"transmissionFactor":0.8,)"
                                          R"("transmissionTexture":{"index":0,"texCoord":1}})");
  EXPECT_TRUE(warnings.messages().empty()) << warnings.messages()[0];
  const Material& m = glass.materials.at(0);
  EXPECT_FLOAT_EQ(m.transmission, 0.8f);
  ASSERT_TRUE(m.transmission_map);
  EXPECT_EQ(m.uv1_maps, texture_slot::transmission);
  EXPECT_EQ(m.alpha_mode, AlphaMode::blend);
  const fs::path dir = test::scratch_dir("clearcoat_sheen");
  const std::string masked = R"({"name":"masked","alphaMode":"MASK",)"
                             R"("extensions":{"KHR_materials_transmission":{"transmissionFactor":1}}})";
  const Mesh cut = load_model(test::write_file(dir, "masked.gltf", test::square_gltf("", 0, "", masked)));
  EXPECT_EQ(cut.materials.at(0).alpha_mode, AlphaMode::mask);
}

// Out of range: clamped with a warning; not a number: the default with a warning; a malformed colour: no sheen.
TEST(GltfLayers, ValuesOutsideTheSpecificationAreWarnedAbout) {
  WarningCapture warnings;
  const Mesh mesh = load_square("bad", R"("KHR_materials_clearcoat":{"clearcoatFactor":3,)"
                                       R"("clearcoatRoughnessFactor":"smooth"},)"
                                       R"("KHR_materials_sheen":{"sheenColorFactor":[2,0,0],)"
                                       R"("sheenRoughnessFactor":-1})");
  const Material& m = mesh.materials.at(0);
  EXPECT_FLOAT_EQ(m.clearcoat, 1.0f);
  EXPECT_FLOAT_EQ(m.clearcoat_roughness, 0.0f);
  EXPECT_EQ(m.sheen_color, glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(m.sheen_roughness, 0.0f);
  const std::vector<std::string>& said = warnings.messages();
  ASSERT_EQ(said.size(), 4u);
  EXPECT_NE(said[0].find("material 'bad': clearcoatFactor must be a number in [0, 1]; clamping it"),
            std::string::npos)
      << said[0];
  EXPECT_NE(said[1].find("clearcoatRoughnessFactor must be a number in [0, 1]; using its default"),
            std::string::npos)
      << said[1];
  EXPECT_NE(said[2].find("sheenColorFactor must be three numbers in [0, 1]"), std::string::npos) << said[2];
  EXPECT_NE(said[3].find("sheenRoughnessFactor"), std::string::npos) << said[3];
}

}  // namespace
}  // namespace facet::clearcoat_sheen_tests
