// test_surface_lanes.cpp - the stock shaders' lane paths draw exactly what their scalar fragment() draws.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "facet/draw.hpp"
#include "facet/environment.hpp"
#include "facet/shaders/stock.hpp"  // the library's own SurfaceShader pipelines, not new ones
#include "facet/texture.hpp"
#include "support/image_asserts.hpp"

namespace facet::test {
namespace {

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// A lit stock shader without its lane function: the scalar definition of the same picture.
template <class S>
struct ScalarOf {
  using Vertex = typename S::Vertex;
  using Varyings = typename S::Varyings;
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;
  S inner;
  VertexOut<Varyings> vertex(const Vertex& v) const { return inner.vertex(v); }
  glm::vec4 fragment(const Fragment<Varyings>& f) const { return inner.fragment(f); }
};
static_assert(LaneShader<SurfaceShader> && LaneShader<GouraudShader> && LaneShader<FlatShader> &&
              LaneShader<UnlitShader> && LaneShader<NormalShader> && LaneShader<DepthShader>);
static_assert(!LaneShader<ScalarOf<SurfaceShader>>);

// An open hemisphere-and-a-bit, so back faces show through the opening, with varied vertex colours and uvs.
struct Geometry {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<glm::vec4> face_colors;
  std::vector<glm::vec3> face_normals;
};

Geometry open_sphere() {
  Geometry g;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float theta = 2.2f * static_cast<float>(i) / n, phi = 6.2831853f * static_cast<float>(j) / n;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      g.vertices.push_back({p, p, {3.0f * j / n, 2.0f * i / n}, {0.5f + 0.5f * p.x, 0.7f, 0.5f - 0.4f * p.z, 1.0f},
                            {0.7f * i / n, 5.0f * j / n}});
    }
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.2f, 1.0f);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto at = [&](int a, int b) { return static_cast<std::uint32_t>(a * (n + 1) + b); };
      g.indices.insert(g.indices.end(),
                       {at(i, j), at(i, j + 1), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
      for (int t = 0; t < 2; ++t) g.face_colors.emplace_back(unit(rng), unit(rng), unit(rng), unit(rng));
    }
  for (std::size_t t = 0; t < g.indices.size(); t += 3) {
    const glm::vec3 a = g.vertices[g.indices[t]].position, b = g.vertices[g.indices[t + 1]].position,
                    c = g.vertices[g.indices[t + 2]].position;
    g.face_normals.push_back(glm::cross(b - a, c - a));
  }
  return g;
}

Framebuffer draw_with(const auto& shader, const Geometry& g) {
  Framebuffer fb(203, 151);
  Renderer renderer(2);
  renderer.clear(fb, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
  RenderState state;
  state.cull = CullMode::none;
  state.defer_shading = true;
  renderer.draw(fb, shader, std::span<const MeshVertex>(g.vertices), g.indices, state);
  renderer.finish(fb);
  return fb;
}

// The shader's lane path draws what its scalar fragment() draws, bit for bit.
template <class S>
void expect_lanes_match(const S& lanes, const Geometry& g, const std::string& name) {
  const Framebuffer expected = draw_with(ScalarOf<S>{lanes}, g);
  const auto drawn = std::count_if(expected.depth().begin(), expected.depth().end(), [](float z) { return z < 1.0f; });
  ASSERT_GT(drawn, 203 * 151 / 5) << name;
  expect_same(expected, draw_with(lanes, g), name.c_str());
}

TEST(SurfaceLanes, EveryMaterialAndLightMatchesTheScalarFragment) {
  const Geometry g = open_sphere();
  std::mt19937 rng(9);
  std::vector<std::uint32_t> texels(32 * 32);
  for (std::uint32_t& t : texels) t = static_cast<std::uint32_t>(rng()) | 0xff000000u;
  Texture texture(32, 32, texels, TexelEncoding::srgb);
  texture.generate_mipmaps();
  const Texture npot(5, 3, std::vector<std::uint32_t>(texels.begin(), texels.begin() + 15));

  const glm::vec3 eye(0.4f, 1.8f, 2.6f);
  const glm::mat4 clip_from_world = glm::perspective(glm::radians(50.0f), 203.0f / 151.0f, 0.1f, 10.0f) *
                                    glm::lookAt(eye, glm::vec3(0.0f), {0, 1, 0});
  struct Case {
    const char* name;
    glm::mat4 world_from_object;
    SpecularModel model;
    glm::vec3 specular;
    bool face_colors;
    const Texture* texture;
    Sampler sampler;
    bool opaque;
  };
  const Case cases[] = {
      {"blinn-phong, vertex colours", glm::mat4(1.0f), SpecularModel::blinn_phong, glm::vec3(0.5f), false, nullptr,
       Sampler{}, false},
      {"phong, face colours, no specular", glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1, 0.2f, 0)),
       SpecularModel::phong, glm::vec3(0.0f), true, nullptr, Sampler{}, true},
      {"mirrored, sRGB texture, trilinear", glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)),
       SpecularModel::phong, glm::vec3(0.3f, 0.6f, 0.9f), false, &texture, Sampler{}, false},
      {"non-power-of-two texture, clamp, nearest", glm::scale(glm::mat4(1.0f), glm::vec3(1.2f, 0.8f, 1.0f)),
       SpecularModel::blinn_phong, glm::vec3(0.4f), true, &npot, Sampler{Filter::nearest, Wrap::clamp, Wrap::mirror},
       false},
  };
  for (const Case& c : cases) {
    LitUniforms lit;
    lit.transforms = ObjectTransforms::make(clip_from_world, c.world_from_object);
    lit.surface.diffuse = glm::vec4(0.9f, 0.8f, 1.0f, 0.75f);
    lit.surface.face_colors = c.face_colors ? g.face_colors.data() : nullptr;
    lit.surface.texture = c.texture;
    lit.surface.sampler = c.sampler;
    lit.surface.opaque = c.opaque;
    lit.lights.add_directional(glm::vec3(-0.3f, 0.5f, 0.8f), glm::vec3(0.8f, 0.9f, 1.0f));
    lit.lights.add_point(glm::vec3(1.5f, 2.0f, 1.0f), glm::vec3(0.6f, 0.3f, 0.2f));
    lit.lights.ambient = glm::vec3(0.12f);
    lit.specular = c.specular;
    lit.shininess = 24.0f;
    lit.specular_model = c.model;
    lit.eye = eye;
    SurfaceShader surface;
    static_cast<LitUniforms&>(surface) = lit;
    expect_lanes_match(surface, g, std::string("surface, ") + c.name);
    // Without a texture the derivative-free variant the scene draws untextured materials with is the same too.
    if (!c.texture)
      expect_same(draw_with(ScalarOf<SurfaceShader>{surface}, g), draw_with(UntexturedSurfaceShader{surface}, g),
                  c.name);
    GouraudShader gouraud;
    static_cast<LitUniforms&>(gouraud) = lit;
    expect_lanes_match(gouraud, g, std::string("Gouraud, ") + c.name);
    FlatShader flat;
    static_cast<LitUniforms&>(flat) = lit;
    flat.face_normals = g.face_normals.data();
    expect_lanes_match(flat, g, std::string("flat, ") + c.name);
    expect_lanes_match(UnlitShader{lit.transforms.clip_from_object, lit.surface}, g, std::string("unlit, ") + c.name);
    NormalShader normal;
    normal.transforms = lit.transforms;
    expect_lanes_match(normal, g, std::string("normals, ") + c.name);
    const glm::mat4 view_from_object = glm::lookAt(eye, glm::vec3(0.0f), {0, 1, 0}) * c.world_from_object;
    expect_lanes_match(DepthShader{lit.transforms.clip_from_object, view_from_object, 1.2f, 4.0f}, g,
                       std::string("depth, ") + c.name);
  }
}

// The physically based shader's lane path: metals and dielectrics, rough and smooth, lit by an environment and two
// lights or by lights and ambient alone, under each tone mapping, mirrored or not.
TEST(SurfaceLanes, PbrMatchesTheScalarFragment) {
  const Geometry g = open_sphere();
  const Environment studio(studio_environment());
  std::mt19937 rng(5);
  std::vector<std::uint32_t> texels(16 * 16);
  for (std::uint32_t& t : texels) t = static_cast<std::uint32_t>(rng()) | 0xff000000u;
  Texture texture(16, 16, texels, TexelEncoding::srgb), linear(16, 16, texels);
  texture.generate_mipmaps();
  // Random alpha too, for the specular strength texture.
  std::vector<std::uint32_t> alphas(16 * 16);
  for (std::uint32_t& t : alphas) t = static_cast<std::uint32_t>(rng());
  Texture translucent(16, 16, alphas);
  translucent.generate_mipmaps();
  const glm::vec3 eye(0.4f, 1.8f, 2.6f);
  const glm::mat4 clip_from_world = glm::perspective(glm::radians(50.0f), 203.0f / 151.0f, 0.1f, 10.0f) *
                                    glm::lookAt(eye, glm::vec3(0.0f), {0, 1, 0});
  struct Case {
    const char* name;
    glm::mat4 world_from_object;
    float metallic, roughness;
    const Environment* environment;
    ToneMapping tone_mapping;
  };
  const Case cases[] = {
      {"dielectric, studio, neutral", glm::mat4(1.0f), 0.0f, 0.5f, &studio, ToneMapping::neutral},
      {"metal, smooth, mirrored, ACES", glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f)), 1.0f, 0.05f,
       &studio, ToneMapping::aces},
      {"half metal, rough, no environment, no tone mapping", glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1, 0.2f, 0)),
       0.5f, 1.0f, nullptr, ToneMapping::none},
  };
  // A directional light, a point light with a range, and a spot whose cone edge crosses the geometry.
  Light spot{Light::Kind::spot, glm::vec3(0.2f, 0.1f, 2.5f), glm::vec3(1.0f, 0.9f, 0.7f), 8.0f};
  spot.spot_direction = glm::vec3(0.0f, 0.0f, -1.0f);
  spot.inner_cone = 0.15f;
  spot.outer_cone = 0.35f;
  Light point{Light::Kind::point, glm::vec3(1.5f, 2.0f, 1.0f), glm::vec3(0.6f, 0.3f, 0.2f), 4.0f};
  point.range = 3.0f;
  PunctualLight lights[] = {
      PunctualLight::from({Light::Kind::directional, glm::vec3(-0.3f, 0.5f, 0.8f), glm::vec3(1.0f, 1.1f, 1.2f), 2.0f}),
      PunctualLight::from(point), PunctualLight::from(spot)};
  // The directional light shadowed by a map of random depths, so every lane reads texels of its own.
  std::vector<float> depths(64 * 64);
  std::mt19937 random(7);
  for (float& d : depths) d = std::uniform_real_distribution<float>(0.3f, 0.7f)(random);
  const ShadowMap shadow(glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.0f, 4.0f) *
                             glm::lookAt(glm::vec3(-0.6f, 1.0f, 1.6f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)),
                         64, std::span<const float>(depths), 0.01f);
  lights[0].shadow = &shadow;
  // Screen-space occlusion over a region of 60 x 40 values from (13, 9) on, within the 102 x 76 of the target: the
  // lanes outside it clamp on every side.
  std::vector<float> open(60 * 40);
  for (float& o : open) o = std::uniform_real_distribution<float>(0.3f, 1.0f)(random);
  for (const Case& c : cases) {
    PbrShader shader;
    shader.transforms = ObjectTransforms::make(clip_from_world, c.world_from_object);
    shader.material.base_color = glm::vec4(0.9f, 0.5f, 0.2f, 0.8f);
    shader.material.metallic = c.metallic;
    shader.material.roughness = c.roughness;
    shader.material.emissive = glm::vec3(0.05f, 0.0f, 0.1f);
    shader.lights = lights;
    shader.ambient = glm::vec3(0.12f);
    shader.screen_occlusion = open.data();
    shader.screen_occlusion_x = 13;
    shader.screen_occlusion_y = 9;
    shader.screen_occlusion_width = 60;
    shader.screen_occlusion_height = 40;
    shader.environment = c.environment;
    shader.eye = eye;
    shader.tone_mapping = c.tone_mapping;
    shader.exposure = 1.3f;
    expect_lanes_match(shader, g, std::string("PBR, ") + c.name);
    expect_same(draw_with(ScalarOf<PbrShader>{shader}, g), draw_with(UntexturedPbrShader{shader}, g), c.name);
    // Every texture the material model reads, and face colours.
    shader.material.face_colors = g.face_colors.data();
    shader.material.base_color_map = &texture;
    shader.material.metallic_roughness_map = &linear;
    shader.material.occlusion_map = &linear;
    shader.material.emissive_map = &texture;
    shader.material.occlusion_strength = 0.7f;
    expect_lanes_match(shader, g, std::string("PBR, textured, ") + c.name);
    // KHR_materials_ior and KHR_materials_specular: another f0, a weaker specular and a colour past 1 (clamped),
    // first alone, then with their textures (strength from a varying alpha) on top of the others.
    PbrShader tinted = shader;
    tinted.material = PbrMaterial{};
    tinted.material.base_color = shader.material.base_color;
    tinted.material.metallic = c.metallic;
    tinted.material.roughness = c.roughness;
    tinted.material.dielectric_f0 = brdf::dielectric_f0(1.8f);
    tinted.material.specular = 0.7f;
    tinted.material.specular_color = glm::vec3(1.6f, 0.8f, 0.3f);
    expect_lanes_match(tinted, g, std::string("PBR, ior and specular, ") + c.name);
    expect_same(draw_with(ScalarOf<PbrShader>{tinted}, g), draw_with(UntexturedPbrShader{tinted}, g), c.name);
    tinted.material = shader.material;
    tinted.material.dielectric_f0 = brdf::dielectric_f0(0.0f);
    tinted.material.specular = 0.9f;
    tinted.material.specular_color = glm::vec3(0.5f, 2.0f, 0.1f);
    tinted.material.specular_map = &translucent;
    tinted.material.specular_color_map = &texture;
    expect_lanes_match(tinted, g, std::string("PBR, textured, ior and specular, ") + c.name);
    // KHR_materials_clearcoat and _sheen: the layers alone, then with their textures (the coat's normal map sends
    // pixels to fragment(), which must agree with itself lane by lane).
    PbrShader layered = shader;
    layered.material = PbrMaterial{};
    layered.material.base_color = shader.material.base_color;
    layered.material.metallic = c.metallic;
    layered.material.roughness = c.roughness;
    layered.material.clearcoat = 0.8f;
    layered.material.clearcoat_roughness = 0.02f;
    layered.material.sheen_color = glm::vec3(0.9f, 0.3f, 0.6f);
    layered.material.sheen_roughness = 0.4f;
    expect_lanes_match(layered, g, std::string("PBR, clearcoat and sheen, ") + c.name);
    expect_same(draw_with(ScalarOf<PbrShader>{layered}, g), draw_with(UntexturedPbrShader{layered}, g), c.name);
    layered.material = shader.material;
    layered.material.clearcoat = 1.0f;
    layered.material.clearcoat_roughness = 0.6f;
    layered.material.clearcoat_map = &linear;
    layered.material.clearcoat_roughness_map = &linear;
    layered.material.sheen_color = glm::vec3(1.0f);
    layered.material.sheen_roughness = 0.9f;
    layered.material.sheen_color_map = &texture;
    layered.material.sheen_roughness_map = &translucent;
    expect_lanes_match(layered, g, std::string("PBR, textured, clearcoat and sheen, ") + c.name);
    layered.material.clearcoat_normal_map = &linear;
    expect_lanes_match(layered, g, std::string("PBR, clearcoat normal map, ") + c.name);
    // TEXCOORD_1: some maps on the second uv set, normal maps included.
    layered.material.uv1_maps = texture_slot::base_color | texture_slot::sheen_color | texture_slot::clearcoat_normal;
    expect_lanes_match(layered, g, std::string("PBR, second uv set, ") + c.name);
    layered.material.clearcoat_normal_map = nullptr;
    expect_lanes_match(layered, g, std::string("PBR, second uv set on lanes, ") + c.name);
    // KHR_materials_transmission, from its factor and then a texture too.
    layered.material.transmission = 0.9f;
    expect_lanes_match(layered, g, std::string("PBR, transmission, ") + c.name);
    layered.material.transmission_map = &linear;
    expect_lanes_match(layered, g, std::string("PBR, textured transmission, ") + c.name);
  }
}

#pragma GCC diagnostic pop

}  // namespace
}  // namespace facet::test
