// test_gltf_specular.cpp - KHR_materials_ior and KHR_materials_specular: what the glTF reader keeps of them, what
// it does with values the specification does not allow, and how they change the physically based shading.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/pbr.hpp"
#include "facet/texture.hpp"
#include "facet/warnings.hpp"
#include "support/gltf_square.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::gltf_specular_tests {
namespace {

namespace fs = std::filesystem;

// The square with one material whose extensions are `extensions` (a JSON object's members), loaded; textures,
// when the extensions name any, come from a 2 x 2 PNG beside the file.
Mesh load_square(const std::string& name, const std::string& extensions, const std::string& top_level = "") {
  const fs::path dir = test::scratch_dir("gltf_specular");
  const std::vector<std::uint8_t> rgba = {255, 0, 0, 128, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 0};
  write_png(dir / "specular.png", 2, 2, rgba);
  const std::string material = R"({"name":")" + name + R"(","extensions":{)" + extensions + "}}";
  return load_model(test::write_file(dir, name + ".gltf", test::square_gltf("", 0, top_level, material)));
}

const std::string kImages = R"(,"images":[{"uri":"specular.png"}],"textures":[{"source":0},{"source":0}])";

TEST(GltfSpecular, ReadsBothExtensions) {
  WarningCapture warnings;
  const Mesh mesh =
      load_square("both",
                  R"("KHR_materials_ior":{"ior":1.33},)"
                  R"("KHR_materials_specular":{"specularFactor":0.25,"specularColorFactor":[2,0.5,0],)"
                  R"("specularTexture":{"index":0},"specularColorTexture":{"index":1}})",
                  R"(,"extensionsUsed":["KHR_materials_ior","KHR_materials_specular"],)"
                  R"("extensionsRequired":["KHR_materials_ior","KHR_materials_specular"])" +
                      kImages);
  EXPECT_TRUE(warnings.messages().empty()) << warnings.messages()[0];
  ASSERT_EQ(mesh.materials.size(), 1u);
  const Material& m = mesh.materials[0];
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_FLOAT_EQ(m.specular_factor, 0.25f);
  // Linear and above 1 allowed: the colour factor is kept as the file gives it.
  EXPECT_EQ(m.specular_color_factor, glm::vec3(2.0f, 0.5f, 0.0f));
  ASSERT_TRUE(m.specular_map && m.specular_color_map);
  EXPECT_EQ(m.specular_map->encoding(), TexelEncoding::linear);
  EXPECT_EQ(m.specular_color_map->encoding(), TexelEncoding::srgb);
  EXPECT_EQ(m.specular_map->width(), 2);
}

TEST(GltfSpecular, DefaultsWithoutTheExtensionsOrTheirMembers) {
  WarningCapture warnings;
  for (const std::string& extensions :
       {std::string(), std::string(R"("KHR_materials_ior":{},"KHR_materials_specular":{})")}) {
    const Mesh mesh = load_square("defaults", extensions);
    const Material& m = mesh.materials.at(0);
    EXPECT_EQ(m.ior, 1.5f);
    EXPECT_EQ(m.specular_factor, 1.0f);
    EXPECT_EQ(m.specular_color_factor, glm::vec3(1.0f));
    EXPECT_FALSE(m.specular_map || m.specular_color_map);
  }
  EXPECT_TRUE(warnings.messages().empty());
}

// ior 0 is the specification's specular-glossiness mode and is kept; the rest fall back to the defaults, warned.
TEST(GltfSpecular, BadValuesAreWarnedAboutAndReplacedByTheDefaults) {
  {
    WarningCapture warnings;
    EXPECT_EQ(load_square("zero", R"("KHR_materials_ior":{"ior":0})").materials.at(0).ior, 0.0f);
    EXPECT_TRUE(warnings.messages().empty());
  }
  for (const std::string ior : {"0.5", "-2", "\"glass\"", "[1.5]"}) {
    WarningCapture warnings;
    EXPECT_EQ(load_square("ior", R"("KHR_materials_ior":{"ior":)" + ior + "}").materials.at(0).ior, 1.5f) << ior;
    ASSERT_EQ(warnings.messages().size(), 1u) << ior;
    EXPECT_NE(warnings.messages()[0].find("ior must be 0 or a finite number of at least 1"), std::string::npos)
        << warnings.messages()[0];
  }
  WarningCapture warnings;
  const Mesh mesh = load_square("specular", R"("KHR_materials_specular":{"specularFactor":-0.5,)"
                                            R"("specularColorFactor":[1,-1,1],"specularColorTexture":{"index":7}})");
  const Material& m = mesh.materials.at(0);
  EXPECT_EQ(m.specular_factor, 1.0f);
  EXPECT_EQ(m.specular_color_factor, glm::vec3(1.0f));
  EXPECT_FALSE(m.specular_color_map);  // a texture the file does not have is no texture
  ASSERT_EQ(warnings.messages().size(), 2u);
  EXPECT_NE(warnings.messages()[0].find("specularFactor"), std::string::npos) << warnings.messages()[0];
  EXPECT_NE(warnings.messages()[1].find("specularColorFactor"), std::string::npos) << warnings.messages()[1];
  // Above 1 is clamped, as the specification bounds it, without a warning.
  EXPECT_EQ(load_square("strong", R"("KHR_materials_specular":{"specularFactor":3})").materials.at(0).specular_factor,
            1.0f);
  EXPECT_EQ(warnings.messages().size(), 2u);
}

TEST(Brdf, DielectricReflectanceFollowsTheIndexOfRefraction) {
  EXPECT_EQ(brdf::dielectric_f0(1.5f), 0.04f);  // the core specification's constant, exactly
  EXPECT_EQ(brdf::dielectric_f0(1.0f), 0.0f);
  EXPECT_EQ(brdf::dielectric_f0(0.0f), 1.0f);  // the specular-glossiness mode
  EXPECT_NEAR(brdf::dielectric_f0(1.33f), 0.02006f, 1e-5f);
}

// A dielectric under one light seen from one direction, with no environment and no ambient light.
brdf::Rgb<float> shade(const PbrMaterial& material, glm::vec3 base) {
  PbrShader shader;
  shader.material = material;
  const PunctualLight light =
      PunctualLight::from({Light::Kind::directional, glm::vec3(0.3f, 0.2f, 1.0f), glm::vec3(1.0f), 2.0f});
  shader.lights = std::span<const PunctualLight>(&light, 1);
  shader.eye = glm::vec3(-0.2f, 0.1f, 3.0f);
  PbrMaterial inputs = material;
  inputs.base_color = glm::vec4(1.0f);
  inputs.metallic = 0.0f;
  inputs.roughness = 0.4f;
  const PbrInputs<float> in = factor_inputs<float>(inputs, {base.r, base.g, base.b}, 1.0f);
  return shader.shade(in, glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f));
}

// A black dielectric shows only its specular reflection: some at ior 1.5 (the default material's, exactly), next
// to none at ior 1, and none with a specular strength of 0. A coloured specular colours the reflection.
TEST(PbrShader, IorAndSpecularSetTheDielectricReflection) {
  PbrMaterial m;
  const brdf::Rgb<float> glass = shade(m, glm::vec3(0.0f));
  EXPECT_GT(glass.r, 0.0f);
  EXPECT_EQ(glass.r, glass.b);
  m.dielectric_f0 = brdf::dielectric_f0(1.5f);
  EXPECT_EQ(shade(m, glm::vec3(0.0f)).g, glass.g);
  m.dielectric_f0 = brdf::dielectric_f0(1.0f);
  const brdf::Rgb<float> air = shade(m, glm::vec3(0.0f));
  // Not exactly 0: Schlick's f90 stays 1 as the specification has it, so (1 - VdotH)^5 of the light remains.
  EXPECT_LT(air.r, 1e-5f * glass.r);
  EXPECT_EQ(air.r, air.g);
  m = PbrMaterial{};
  m.specular = 0.0f;
  EXPECT_EQ(shade(m, glm::vec3(0.0f)).g, 0.0f);
  m = PbrMaterial{};
  m.specular_color = glm::vec3(3.0f, 1.0f, 0.0f);
  const brdf::Rgb<float> tinted = shade(m, glm::vec3(0.0f));
  EXPECT_GT(tinted.r, glass.r);
  EXPECT_LT(tinted.b, glass.b);
}

// Without specular reflection a white dielectric keeps all its diffuse light: more than with it, and the same
// whatever the specular colour; a coloured specular takes light out of the diffuse part evenly (its largest
// channel), adding no complementary tint to it.
TEST(PbrShader, SpecularStrengthShiftsEnergyToTheDiffusePart) {
  PbrMaterial m;
  const brdf::Rgb<float> full = shade(m, glm::vec3(1.0f));
  m.specular = 0.0f;
  const brdf::Rgb<float> none = shade(m, glm::vec3(1.0f));
  m.specular_color = glm::vec3(0.0f, 1.0f, 2.0f);
  const brdf::Rgb<float> none_tinted = shade(m, glm::vec3(1.0f));
  EXPECT_EQ(none.r, none_tinted.r);
  EXPECT_EQ(none.b, none_tinted.b);
  EXPECT_EQ(none.r, none.b);
  // Diffuse alone: E NdotL / pi, the light's irradiance 2 along its direction.
  const float n_dot_l = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f)).z;
  EXPECT_NEAR(none.g, 2.0f * n_dot_l / brdf::kPi, 1e-5f);
  EXPECT_GT(full.g, 0.0f);
  // A red-only specular colour: the diffuse loses as much in every channel as a grey f0 of 0.04 takes, while green
  // and blue reflect only towards grazing (f90 stays 1), less than the grey material does.
  m.specular = 1.0f;
  m.specular_color = glm::vec3(1.0f, 0.0f, 0.0f);
  const brdf::Rgb<float> red = shade(m, glm::vec3(1.0f));
  EXPECT_EQ(red.g, red.b);
  EXPECT_GT(red.r, red.g);
  EXPECT_EQ(red.r, full.r);
  EXPECT_LT(red.g, full.g);
}

}  // namespace
}  // namespace facet::gltf_specular_tests
