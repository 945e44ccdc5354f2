// test_shaders.cpp - the stock shaders on small scenes: exact lit colours, specular models, textures, normals, depth.
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/shaders/stock.hpp"

namespace facet::shaders_tests {
namespace {

constexpr int kSize = 64;
const glm::vec3 kEye(0.0f, 0.0f, 3.0f);

static_assert(Shader<UnlitShader> && Shader<FlatShader> && Shader<GouraudShader> && Shader<SurfaceShader> &&
              Shader<NormalShader> && Shader<DepthShader> && Shader<LineShader>);

glm::mat4 clip_from_world() {
  return glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f) *
         glm::lookAt(kEye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
}

struct TestMesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::uint32_t> indices;
};

// A 2x2 square in the plane z, facing +z, uv (0, 0) at the bottom left.
TestMesh quad(float z = 0.0f, glm::vec4 color = glm::vec4(1.0f)) {
  TestMesh m;
  const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (const glm::vec2 c : corners) m.vertices.push_back({glm::vec3(c, z), {0, 0, 1}, c * 0.5f + 0.5f, color});
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// A cube of side 1 around the origin sharing its 8 corners, so each corner's normal points diagonally outwards.
TestMesh smooth_cube() {
  TestMesh m;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 p((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
    m.vertices.push_back({p, glm::normalize(p), glm::vec2(0.0f), glm::vec4(1.0f)});
  }
  const std::uint32_t quads[6][4] = {{4, 5, 7, 6}, {1, 0, 2, 3}, {5, 1, 3, 7},
                                     {0, 4, 6, 2}, {6, 7, 3, 2}, {0, 1, 5, 4}};
  for (const auto& q : quads) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

template <class S>
void draw(Framebuffer& fb, const S& shader, const TestMesh& mesh, const RenderState& state = {}) {
  Renderer renderer(2);
  renderer.clear(fb, glm::vec4(0, 0, 0, 1));
  renderer.draw(fb, shader, std::span<const MeshVertex>(mesh.vertices), mesh.indices, state);
  renderer.finish(fb);
}

void expect_pixel(const Framebuffer& fb, int x, int y, glm::vec3 expected, float tolerance_levels = 1.0f) {
  const glm::vec4 got = unpack_rgba8(fb.pixel(x, y)) * 255.0f;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], static_cast<float>(pack_channel(expected[c])), tolerance_levels)
        << "pixel (" << x << ", " << y << ") channel " << c;
}

// Where the ray through the centre of pixel (x, y) meets the plane z = 0.
glm::vec3 world_on_plane(int x, int y) {
  const glm::mat4 inv = glm::inverse(clip_from_world());
  const glm::vec2 ndc(2.0f * (x + 0.5f) / kSize - 1.0f, 1.0f - 2.0f * (y + 0.5f) / kSize);
  glm::vec4 a = inv * glm::vec4(ndc, -1.0f, 1.0f), b = inv * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 p0 = glm::vec3(a) / a.w, p1 = glm::vec3(b) / b.w;
  return p0 + (p1 - p0) * (p0.z / (p0.z - p1.z));
}

LightBlock one_light(glm::vec3 towards, glm::vec3 ambient) {
  LightBlock lights;
  lights.ambient = ambient;
  lights.add_directional(towards, glm::vec3(1.0f));
  return lights;
}

template <class S>
S lit(LightBlock lights, glm::vec4 diffuse, glm::vec3 specular = glm::vec3(0.0f), float shininess = 32.0f) {
  S s;
  s.transforms = ObjectTransforms::make(clip_from_world(), glm::mat4(1.0f));
  s.surface.diffuse = diffuse;
  s.lights = lights;
  s.specular = specular;
  s.shininess = shininess;
  s.eye = kEye;
  return s;
}

TEST(StockShader, SurfaceHeadOnDirectionalIsAmbientPlusDiffuse) {
  Framebuffer fb(kSize, kSize);
  const glm::vec4 diffuse(0.6f, 0.4f, 0.2f, 1.0f);
  draw(fb, lit<SurfaceShader>(one_light({0, 0, 1}, glm::vec3(0.1f)), diffuse), quad());
  for (const auto& [x, y] : {std::pair{32, 32}, {10, 12}, {52, 40}}) expect_pixel(fb, x, y, glm::vec3(diffuse) * 1.1f);
  expect_pixel(fb, 1, 1, glm::vec3(0.0f), 0.0f);  // outside the quad: the clear colour
}

TEST(StockShader, PhongAndBlinnPhongSpecularFollowTheirFormulas) {
  const glm::vec3 l = glm::normalize(glm::vec3(1, 0, 1));
  for (const SpecularModel model : {SpecularModel::phong, SpecularModel::blinn_phong}) {
    Framebuffer fb(kSize, kSize);
    auto shader = lit<SurfaceShader>(one_light(l, glm::vec3(0.0f)), glm::vec4(0, 0, 0, 1), glm::vec3(1.0f), 8.0f);
    shader.specular_model = model;
    draw(fb, shader, quad());
    for (const auto& [x, y] : {std::pair{32, 32}, {20, 40}, {45, 25}}) {
      const glm::vec3 v = glm::normalize(kEye - world_on_plane(x, y));
      const glm::vec3 n(0, 0, 1);
      const float s =
          model == SpecularModel::phong ? glm::dot(glm::reflect(-l, n), v) : glm::dot(n, glm::normalize(l + v));
      expect_pixel(fb, x, y, glm::vec3(std::pow(std::max(s, 0.0f), 8.0f)));
    }
    // Seen head-on with the light at 45 degrees: cos^8 of 45 degrees for Phong, of 22.5 degrees for Blinn-Phong.
    const float centre = unpack_rgba8(fb.pixel(32, 32)).r;
    if (model == SpecularModel::phong) EXPECT_LT(centre, 0.1f);
    else EXPECT_GT(centre, 0.45f);
  }
}

TEST(StockShader, PointLightUsesTheDirectionToTheLight) {
  Framebuffer fb(kSize, kSize);
  LightBlock lights;
  lights.add_point({0.0f, 0.0f, 1.0f}, glm::vec3(1.0f));
  draw(fb, lit<SurfaceShader>(lights, glm::vec4(1.0f)), quad());
  for (const auto& [x, y] : {std::pair{32, 32}, {10, 10}, {50, 20}}) {
    const glm::vec3 p = world_on_plane(x, y);
    expect_pixel(fb, x, y, glm::vec3(glm::normalize(glm::vec3(0, 0, 1) - p).z));
  }
  EXPECT_GT(unpack_rgba8(fb.pixel(32, 32)).r, unpack_rgba8(fb.pixel(8, 8)).r + 0.2f);
}

TEST(StockShader, FlatGouraudAndPerPixelDifferOnASmoothCube) {
  // The front face's corners have normals (+-1, +-1, 1)/sqrt(3): Gouraud lights each corner with 1/sqrt(3) and
  // interpolates that constant; flat uses the face normal (0, 0, 1); per-pixel peaks at the face centre.
  const TestMesh cube = smooth_cube();
  std::vector<glm::vec3> face_normals;
  for (std::size_t t = 0; t < cube.indices.size(); t += 3) {
    const glm::vec3 a = cube.vertices[cube.indices[t]].position, b = cube.vertices[cube.indices[t + 1]].position,
                    c = cube.vertices[cube.indices[t + 2]].position;
    face_normals.push_back(glm::normalize(glm::cross(b - a, c - a)));
  }
  const LightBlock lights = one_light({0, 0, 1}, glm::vec3(0.1f));
  const glm::vec4 diffuse(0.8f, 0.6f, 0.4f, 1.0f);
  const int points[3][2] = {{32, 32}, {27, 28}, {37, 36}};

  Framebuffer flat_fb(kSize, kSize);
  FlatShader flat = lit<FlatShader>(lights, diffuse);
  flat.face_normals = face_normals.data();
  draw(flat_fb, flat, cube);
  for (const auto& p : points) expect_pixel(flat_fb, p[0], p[1], glm::vec3(diffuse) * 1.1f);

  Framebuffer gouraud_fb(kSize, kSize);
  draw(gouraud_fb, lit<GouraudShader>(lights, diffuse), cube);
  for (const auto& p : points) expect_pixel(gouraud_fb, p[0], p[1], glm::vec3(diffuse) * (0.1f + 1 / std::sqrt(3.0f)));

  Framebuffer surface_fb(kSize, kSize);
  draw(surface_fb, lit<SurfaceShader>(lights, diffuse), cube);
  expect_pixel(surface_fb, 32, 32, glm::vec3(diffuse) * 1.1f, 3.0f);
  EXPECT_LT(unpack_rgba8(surface_fb.pixel(27, 27)).r, unpack_rgba8(surface_fb.pixel(32, 32)).r);
}

TEST(StockShader, UnlitShowsTextureTimesVertexColour) {
  const auto rgba = [](std::uint32_t r, std::uint32_t g, std::uint32_t b) { return r | g << 8 | b << 16 | 255u << 24; };
  const Texture texture(2, 2, {rgba(255, 0, 0), rgba(0, 255, 0), rgba(0, 0, 255), rgba(255, 255, 255)});
  UnlitShader shader{clip_from_world(), {glm::vec4(1.0f), nullptr, &texture, Sampler{Filter::nearest}}};
  Framebuffer fb(kSize, kSize);
  draw(fb, shader, quad(0.0f, glm::vec4(1.0f, 1.0f, 0.5f, 1.0f)));
  // v = 0 is the bottom of the quad, which is the bottom of the image.
  expect_pixel(fb, 16, 48, {1, 0, 0});
  expect_pixel(fb, 48, 48, {0, 1, 0});
  expect_pixel(fb, 16, 16, {0, 0, 0.5f});
  expect_pixel(fb, 48, 16, {1, 1, 0.5f});
}

TEST(StockShader, UnlitFaceColoursFollowThePrimitiveIndex) {
  // A cube seen from (2, 2.5, 3): the +x, +y and +z faces are visible; each face has its own colour.
  const TestMesh cube = smooth_cube();
  const glm::vec4 colors[6] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}};
  std::vector<glm::vec4> face_colors;
  for (const glm::vec4& c : colors) face_colors.insert(face_colors.end(), {c, c});
  const glm::mat4 clip = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f) *
                         glm::lookAt(glm::vec3(2.0f, 2.5f, 3.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
  UnlitShader shader{clip, {glm::vec4(1.0f), face_colors.data(), nullptr, {}}};
  Framebuffer fb(kSize, kSize);
  draw(fb, shader, cube);
  // Face centres: +z (face 0), +x (face 2), +y (face 4).
  const std::pair<glm::vec3, int> faces[3] = {{{0, 0, 0.5f}, 0}, {{0.5f, 0, 0}, 2}, {{0, 0.5f, 0}, 4}};
  for (const auto& [centre, face] : faces) {
    const glm::vec4 c = clip * glm::vec4(centre, 1.0f);
    const int x = static_cast<int>((c.x / c.w + 1) * 0.5f * kSize);
    const int y = static_cast<int>((1 - c.y / c.w) * 0.5f * kSize);
    expect_pixel(fb, x, y, glm::vec3(colors[face]), 0.0f);
  }
}

TEST(StockShader, NormalShaderShowsWorldNormals) {
  Framebuffer fb(kSize, kSize);
  draw(fb, NormalShader{ObjectTransforms::make(clip_from_world(), glm::mat4(1.0f))}, quad());
  expect_pixel(fb, 32, 32, {0.5f, 0.5f, 1.0f}, 0.0f);

  // Turned 30 degrees about +y the normal is (sin 30, 0, cos 30).
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 1, 0));
  draw(fb, NormalShader{ObjectTransforms::make(clip_from_world(), turn)}, quad());
  expect_pixel(fb, 32, 32, glm::vec3(0.5f, 0.0f, std::sqrt(3.0f) / 2) * 0.5f + 0.5f);
}

TEST(StockShader, NormalMatrixKeepsNormalsPerpendicularUnderNonUniformScale) {
  const glm::mat4 stretch = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, 1.0f));
  const ObjectTransforms t = ObjectTransforms::make(glm::mat4(1.0f), stretch);
  // The plane x + y = 0 becomes 0.5 x + y = 0 once x is stretched by 2.
  const glm::vec3 n = glm::normalize(t.normal_from_object * glm::vec3(1, 1, 0));
  const glm::vec3 tangent = glm::vec3(stretch * glm::vec4(1, -1, 0, 0));
  EXPECT_NEAR(glm::dot(n, tangent), 0.0f, 1e-6f);
  EXPECT_NEAR(n.x, 1.0f / std::sqrt(5.0f), 1e-6f);
}

TEST(StockShader, DepthShaderIsLinearAndDarkensWithDistance) {
  const glm::mat4 view = glm::lookAt(kEye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  const glm::mat4 clip = clip_from_world();
  Framebuffer fb(kSize, kSize);
  draw(fb, DepthShader{clip, view, 1.0f, 5.0f}, quad(0.0f));  // distance 3: halfway
  expect_pixel(fb, 32, 32, glm::vec3(0.5f));
  draw(fb, DepthShader{clip, view, 1.0f, 5.0f}, quad(-1.0f));  // distance 4
  expect_pixel(fb, 32, 32, glm::vec3(0.25f));

  // A floor tilted away from the camera: grey falls monotonically up the image.
  const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), glm::radians(-60.0f), glm::vec3(1, 0, 0));
  draw(fb, DepthShader{clip * tilt, view * tilt, 1.0f, 5.0f}, quad());
  float previous = 2.0f;
  int rows = 0;
  for (int y = kSize - 1; y >= 0; --y) {
    if (fb.depth_at(32, y) >= 1.0f) continue;
    const float grey = unpack_rgba8(fb.pixel(32, y)).r;
    EXPECT_LE(grey, previous) << "row " << y;
    previous = grey;
    ++rows;
  }
  EXPECT_GT(rows, 10);
}

TEST(StockShader, LineShaderDrawsItsColour) {
  const std::vector<MeshVertex> vertices = {{{-1, 0, 0}, {0, 0, 1}, {}, glm::vec4(1)},
                                            {{1, 0, 0}, {0, 0, 1}, {}, glm::vec4(1)}};
  const std::vector<std::uint32_t> indices = {0, 1};
  Framebuffer fb(kSize, kSize);
  Renderer renderer(1);
  renderer.clear(fb, glm::vec4(0, 0, 0, 1));
  renderer.draw_lines(fb, LineShader{clip_from_world(), glm::vec4(0, 1, 0, 1)}, std::span<const MeshVertex>(vertices),
                      indices);
  renderer.finish(fb);
  int lit_in_column = 0;
  for (int y = 0; y < kSize; ++y) lit_in_column += fb.pixel(32, y) == pack_rgba8(glm::vec4(0, 1, 0, 1));
  EXPECT_EQ(lit_in_column, 1);
  expect_pixel(fb, 32, 10, glm::vec3(0.0f), 0.0f);
}

TEST(StockShader, LightTermsMatchTheReferenceFormula) {
  // BENCHMARK.md section 7 with N = (0, 0, 1), L = normalize(0.4, 0.7, 0.6) and the eye straight above the point.
  const LightBlock lights = one_light({0.4f, 0.7f, 0.6f}, glm::vec3(0.15f));
  const glm::vec3 l = glm::normalize(glm::vec3(0.4f, 0.7f, 0.6f)), n(0, 0, 1), v(0, 0, 1);
  const glm::vec3 albedo(0.9f, 0.5f, 0.2f);
  const glm::vec3 got = shade_lit(lights, albedo, glm::vec3(0.4f), 32.0f, SpecularModel::phong, n, glm::vec3(0), v);
  const glm::vec3 r = -l + 2.0f * glm::dot(n, l) * n;
  const glm::vec3 want = 0.15f * albedo + glm::dot(n, l) * albedo + 0.4f * std::pow(glm::dot(r, v), 32.0f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-6f);
}

TEST(StockShader, LightBlockFromSceneOptions) {
  SceneOptions options;
  options.ambient = glm::vec3(0.2f);
  options.lights.clear();
  for (int i = 0; i < 6; ++i) options.lights.push_back({Light::Kind::directional, {0, 0, 2}, {1, 0.5f, 0}, 2.0f});
  options.lights[1] = {Light::Kind::point, {1, 2, 3}, glm::vec3(1.0f), 0.5f};
  const LightBlock block = make_light_block(options);
  EXPECT_EQ(block.count, kMaxLights);
  EXPECT_EQ(block.vector_kind[0], glm::vec4(0, 0, 1, 0));
  EXPECT_EQ(block.color[0], glm::vec3(2, 1, 0));
  EXPECT_EQ(block.vector_kind[1], glm::vec4(1, 2, 3, 1));
  EXPECT_EQ(block.color[1], glm::vec3(0.5f));
  EXPECT_EQ(block.ambient, glm::vec3(0.2f));
}

}  // namespace
}  // namespace facet::shaders_tests
