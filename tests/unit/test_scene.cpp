// test_scene.cpp - the Scene: frustum rejection, drawing modes, materials, textures, computed normals, linear depth.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/scene.hpp"
#include "scene/prepared_mesh.hpp"

namespace facet::scene_tests {
namespace {

constexpr int kSize = 64;
const glm::vec4 kClear(0.0f, 0.0f, 0.0f, 1.0f);
const glm::vec4 kRed(1, 0, 0, 1), kBlue(0, 0, 1, 1);

View make_view(glm::vec3 eye, float near = 0.1f, float far = 100.0f) {
  return {glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0, 1, 0)), glm::perspective(glm::radians(45.0f), 1.0f, near, far),
          near, far};
}

// A w x h rectangle in the plane z, facing +z, centred at (cx, cy).
void add_quad(Mesh& m, float z, float w = 2.0f, float h = 2.0f, float cx = 0.0f, float cy = 0.0f) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
    m.positions.emplace_back(cx + c.x * w / 2, cy + c.y * h / 2, z);
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// A cube of side 1 around the origin with 8 shared corners; faces +z, -z, +x, -x, +y, -y, two triangles each.
Mesh cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
  const std::uint32_t quads[6][4] = {{4, 5, 7, 6}, {1, 0, 2, 3}, {5, 1, 3, 7},
                                     {0, 4, 6, 2}, {6, 7, 3, 2}, {0, 1, 5, 4}};
  for (const auto& q : quads) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

Instance instance(Mesh mesh, glm::mat4 world_from_object = glm::mat4(1.0f)) {
  return {std::make_shared<const Mesh>(std::move(mesh)), world_from_object};
}

struct Frame {
  Framebuffer fb{kSize, kSize};
  std::size_t drawn = 0;
};

Frame render(Scene& scene, const View& view, const SceneOptions& options) {
  Frame frame;
  Renderer renderer(2);
  renderer.clear(frame.fb, kClear);
  frame.drawn = scene.render(renderer, frame.fb, view, options);
  renderer.finish(frame.fb);
  return frame;
}

SceneOptions unlit() {
  SceneOptions options;
  options.shading = Shading::unlit;
  return options;
}

// Pixel (column, row) of a world point.
glm::vec2 project(const View& view, glm::vec3 p) {
  const glm::vec4 c = view.clip_from_view * view.view_from_world * glm::vec4(p, 1.0f);
  return {(c.x / c.w + 1.0f) * 0.5f * kSize, (1.0f - c.y / c.w) * 0.5f * kSize};
}

float distance_to_segment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const float t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0f, 1.0f);
  return glm::length(p - (a + t * (b - a)));
}

TEST(SceneFrustum, SphereInFrustumPerspective) {
  const View view = make_view({0, 0, 3});
  const glm::mat4 m = view.clip_from_view * view.view_from_world;
  EXPECT_TRUE(sphere_in_frustum(m, {0, 0, 0}, 0.5f));
  EXPECT_FALSE(sphere_in_frustum(m, {0, 0, 5}, 0.5f));     // behind the camera
  EXPECT_FALSE(sphere_in_frustum(m, {0, 0, 3.2f}, 0.1f));  // just behind the eye
  EXPECT_TRUE(sphere_in_frustum(m, {0, 0, 3}, 10.0f));     // contains the camera
  // The left plane passes x = -3 tan(22.5 deg) = -1.2426 at z = 0; the centre (-1.5, 0, 0) is 0.2378 outside it.
  EXPECT_TRUE(sphere_in_frustum(m, {-1.5f, 0, 0}, 0.3f));   // straddles the plane
  EXPECT_FALSE(sphere_in_frustum(m, {-1.5f, 0, 0}, 0.2f));  // just outside
  EXPECT_FALSE(sphere_in_frustum(m, {0, 1.5f, 0}, 0.2f));
  EXPECT_FALSE(sphere_in_frustum(m, {0, 0, -200}, 1.0f));   // beyond the far plane (z = -97)
  EXPECT_TRUE(sphere_in_frustum(m, {0, 0, -97.5f}, 1.0f));  // straddles it
}

TEST(SceneFrustum, SphereInFrustumOrthographic) {
  const glm::mat4 m = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
  EXPECT_TRUE(sphere_in_frustum(m, {1.2f, 0, -5}, 0.3f));
  EXPECT_FALSE(sphere_in_frustum(m, {1.2f, 0, -5}, 0.1f));
  EXPECT_FALSE(sphere_in_frustum(m, {0, 0, 1}, 0.5f));  // behind the eye
  EXPECT_TRUE(sphere_in_frustum(m, {0, 0, -0.05f}, 0.1f));
}

TEST(SceneFrustum, InstanceOutsideTheFrustumIsRejected) {
  Scene scene;
  scene.add(instance(cube(), glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0))));
  Frame empty;
  Renderer renderer(1);
  renderer.clear(empty.fb, glm::vec4(0.2f, 0.3f, 0.4f, 1.0f));
  renderer.finish(empty.fb);
  const std::vector<std::uint32_t> color(empty.fb.color().begin(), empty.fb.color().end());
  const std::vector<float> depth(empty.fb.depth().begin(), empty.fb.depth().end());
  EXPECT_EQ(scene.render(renderer, empty.fb, make_view({0, 0, 3}), SceneOptions{}), 0u);
  renderer.finish(empty.fb);
  EXPECT_TRUE(std::equal(color.begin(), color.end(), empty.fb.color().begin()));
  EXPECT_TRUE(std::equal(depth.begin(), depth.end(), empty.fb.depth().begin()));

  scene.add(instance(cube()));
  scene.add(scene.instances().front());  // the same mesh again, still outside
  EXPECT_EQ(scene.size(), 3u);
  EXPECT_EQ(render(scene, make_view({0, 0, 3}), SceneOptions{}).drawn, 1u);
}

TEST(SceneModes, WireframeDrawsOnlyNearEdges) {
  Mesh m;
  add_quad(m, 0.0f);
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({0, 0, 3});
  SceneOptions options;
  options.wireframe = true;
  options.color = kRed;
  const Frame f = render(scene, view, options);
  EXPECT_EQ(f.drawn, 1u);
  std::vector<std::pair<glm::vec2, glm::vec2>> edges;  // the four sides and the diagonal 0-2
  const int pairs[5][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 2}};
  for (const auto& e : pairs) edges.push_back({project(view, m.positions[e[0]]), project(view, m.positions[e[1]])});
  int lit = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (f.fb.pixel(x, y) == pack_rgba8(kClear)) continue;
      EXPECT_EQ(f.fb.pixel(x, y), pack_rgba8(kRed));
      float nearest = 1e9f;
      for (const auto& [a, b] : edges) nearest = std::min(nearest, distance_to_segment({x + 0.5f, y + 0.5f}, a, b));
      EXPECT_LT(nearest, 1.5f) << "pixel " << x << ", " << y;
      ++lit;
    }
  EXPECT_GT(lit, 200);
  const glm::vec2 inside = project(view, {0.5f, -0.3f, 0.0f});  // inside triangle 0-1-2, away from its edges
  EXPECT_EQ(f.fb.pixel(static_cast<int>(inside.x), static_cast<int>(inside.y)), pack_rgba8(kClear));
}

TEST(SceneModes, EdgesShowVisibleEdgesAndHideBackEdges) {
  const Mesh m = cube();
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({1.6f, 2.2f, 3.4f});
  SceneOptions options = unlit();
  options.color = glm::vec4(1.0f);
  options.edges = true;
  options.edge_color = kRed;
  const Frame f = render(scene, view, options);

  // Edges of the visible faces (+z, +x, +y: triangles 0-1, 4-5, 8-9), diagonals included.
  std::vector<std::pair<glm::vec2, glm::vec2>> visible;
  for (const int t : {0, 1, 4, 5, 8, 9})
    for (int k = 0; k < 3; ++k)
      visible.push_back({project(view, m.positions[m.indices[3 * t + k]]),
                         project(view, m.positions[m.indices[3 * t + (k + 1) % 3]])});
  const auto count_red = [&](glm::vec2 p) {
    int red = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        red += f.fb.pixel(static_cast<int>(p.x) + dx, static_cast<int>(p.y) + dy) == pack_rgba8(kRed);
    return red;
  };
  // Visible edges: those meeting at the front corner (+, +, +), and a silhouette edge.
  for (const glm::vec3 mid :
       {glm::vec3(0, 0.5f, 0.5f), glm::vec3(0.5f, 0, 0.5f), glm::vec3(0.5f, 0.5f, 0), glm::vec3(0.5f, -0.5f, 0)})
    EXPECT_GE(count_red(project(view, mid)), 1) << mid.x << " " << mid.y << " " << mid.z;
  // Along the visible edges the line must win the depth test everywhere, not just somewhere: sample each edge of
  // the visible triangles and require red at the sample's pixel or a 4-neighbour.
  int on_line = 0, samples = 0;
  for (const auto& [a, b] : visible)
    for (int step = 1; step < 20; ++step) {
      const glm::vec2 p = a + (b - a) * (step / 20.0f);
      const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
      const std::uint32_t red = pack_rgba8(kRed);
      ++samples;
      on_line += f.fb.pixel(x, y) == red || f.fb.pixel(x + 1, y) == red || f.fb.pixel(x - 1, y) == red ||
                 f.fb.pixel(x, y + 1) == red || f.fb.pixel(x, y - 1) == red;
    }
  EXPECT_EQ(on_line, samples);  // with no depth offset about 1 in 8 samples is lost to z-fighting
  // Hidden edges: points along the edges of the back faces (-z, -x, -y), where they are clear of visible edges.
  int checked = 0;
  for (const int t : {2, 3, 6, 7, 10, 11})
    for (int k = 0; k < 3; ++k)
      for (int step = 1; step < 10; ++step) {
        const glm::vec3 a = m.positions[m.indices[3 * t + k]], b = m.positions[m.indices[3 * t + (k + 1) % 3]];
        const glm::vec2 p = project(view, a + (b - a) * (step / 10.0f));
        float nearest = 1e9f;
        for (const auto& [va, vb] : visible) nearest = std::min(nearest, distance_to_segment(p, va, vb));
        if (nearest < 3.0f) continue;  // too close to a visible edge to tell them apart
        ++checked;
        EXPECT_EQ(count_red(p), 0) << "triangle " << t << " edge " << k << " at " << step / 10.0f;
        EXPECT_EQ(f.fb.pixel(static_cast<int>(p.x), static_cast<int>(p.y)), pack_rgba8(glm::vec4(1.0f)));
      }
  EXPECT_GE(checked, 10);
}

TEST(SceneModes, PainterSortsWhereNoDepthTestDoesNot) {
  // The near red quad comes first in the index order, the far blue one second; they overlap in the centre.
  Mesh m;
  add_quad(m, 0.5f, 1.0f, 1.0f);
  add_quad(m, -0.5f, 2.0f, 2.0f, 0.3f, 0.2f);
  m.face_colors = {kRed, kRed, kBlue, kBlue};
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({0, 0, 3});
  const auto centre = [&](const SceneOptions& o) { return render(scene, view, o).fb.pixel(32, 32); };

  SceneOptions options = unlit();
  EXPECT_EQ(centre(options), pack_rgba8(kRed));  // depth buffer
  options.depth_test = false;
  EXPECT_EQ(centre(options), pack_rgba8(kBlue));  // last drawn wins
  options.painter = true;
  EXPECT_EQ(centre(options), pack_rgba8(kRed));  // farthest first

  // Across instances too: the near red instance added first, the far blue one second.
  Mesh near_quad, far_quad;
  add_quad(near_quad, 0.5f, 1.0f, 1.0f);
  near_quad.face_colors = {kRed, kRed};
  add_quad(far_quad, -0.5f);
  far_quad.face_colors = {kBlue, kBlue};
  Scene two;
  two.add(instance(near_quad));
  two.add(instance(far_quad));
  options = unlit();
  const Frame depth_tested = render(two, view, options);
  EXPECT_EQ(depth_tested.drawn, 2u);
  EXPECT_EQ(depth_tested.fb.pixel(32, 32), pack_rgba8(kRed));
  EXPECT_EQ(depth_tested.fb.pixel(13, 32), pack_rgba8(kBlue));  // only the far quad
  options.depth_test = false;
  EXPECT_EQ(render(two, view, options).fb.pixel(32, 32), pack_rgba8(kBlue));
  options.painter = true;
  EXPECT_EQ(render(two, view, options).fb.pixel(32, 32), pack_rgba8(kRed));
}

TEST(SceneMaterials, OneDrawPerMaterialKeepsFaceColoursAligned) {
  // Materials alternate by face, so grouping reorders the triangles; each face's colour must follow it.
  Mesh m = cube();
  m.materials = {Material{"full", glm::vec4(1.0f), {}, 32, {}},
                 Material{"half", glm::vec4(0.5f, 0.5f, 0.5f, 1), {}, 32, {}}};
  const glm::vec4 colors[6] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}};
  for (int face = 0; face < 6; ++face) {
    m.face_colors.insert(m.face_colors.end(), {colors[face], colors[face]});
    m.face_materials.insert(m.face_materials.end(), {face % 2, face % 2});
  }
  m.face_materials[0] = 1;  // even the two triangles of one face may differ
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({2.0f, 2.5f, 3.0f});
  const Frame f = render(scene, view, unlit());
  // +z face: triangle 0 uses "half", triangle 1 "full"; +x face (2): "full"; +y face (4): "full".
  const std::pair<glm::vec3, glm::vec4> probes[4] = {{{0.25f, -0.2f, 0.5f}, colors[0] * 0.5f},
                                                     {{-0.25f, 0.2f, 0.5f}, colors[0]},
                                                     {{0.5f, 0.0f, 0.0f}, colors[2]},
                                                     {{0.0f, 0.5f, 0.0f}, colors[4]}};
  for (const auto& [point, want] : probes) {
    const glm::vec2 p = project(view, point);
    EXPECT_EQ(f.fb.pixel(static_cast<int>(p.x), static_cast<int>(p.y)), pack_rgba8(glm::vec4(glm::vec3(want), 1)))
        << point.x << " " << point.y << " " << point.z;
  }
}

TEST(SceneMaterials, MissingTextureWarnsOnceAndDrawsWithout) {
  Mesh m;
  add_quad(m, 0.0f);
  m.uvs.assign(4, glm::vec2(0.5f));
  m.materials = {Material{"m", glm::vec4(0, 1, 0, 1), {}, 32, "/nonexistent/facet-test/missing.png"}};
  m.face_materials = {0, 0};
  Scene scene;
  testing::internal::CaptureStderr();
  scene.add(instance(m));
  scene.add(instance(m));  // another mesh with the same texture: no second warning
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.rfind("facet: warning: /nonexistent/facet-test/missing.png: ", 0), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_EQ(render(scene, make_view({0, 0, 3}), unlit()).fb.pixel(32, 32), pack_rgba8(glm::vec4(0, 1, 0, 1)));
}

// An unlit material (glTF's KHR_materials_unlit) draws with its colour alone under the automatic shading, where a
// lit one facing the same way is shaded.
TEST(SceneMaterials, UnlitMaterialIgnoresTheLights) {
  const glm::vec4 colour(0.2f, 0.6f, 0.4f, 1.0f);
  const auto centre_pixel = [&](bool unlit) {
    Mesh m;
    add_quad(m, 0.0f);
    Material material{"m", colour, {}, 32, {}};
    material.unlit = unlit;
    m.materials = {material};
    m.face_materials = {0, 0};
    Scene scene;
    scene.add(instance(m));
    return render(scene, make_view({0.5f, 0.8f, 3.0f}), SceneOptions{}).fb.pixel(32, 32);
  };
  EXPECT_EQ(centre_pixel(true), pack_rgba8(colour));
  EXPECT_NE(centre_pixel(false), pack_rgba8(colour));
}

TEST(SceneShading, MissingNormalsAreComputedAndDefaultMaterialIsLit) {
  Mesh m;
  add_quad(m, 0.0f);
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({0, 0, 3});
  SceneOptions options;
  options.shading = Shading::normals;
  EXPECT_EQ(render(scene, view, options).fb.pixel(32, 32), pack_rgba8({0.5f, 0.5f, 1.0f, 1.0f}));

  // Blinn-Phong with the default material (specular 0.4, shininess 32); the highlight peaks head-on.
  options.shading = Shading::blinn_phong;
  options.lights = {Light{Light::Kind::directional, {0, 0, 1}, glm::vec3(1.0f), 1.0f}};
  options.ambient = glm::vec3(0.1f);
  options.color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  const glm::vec4 got = unpack_rgba8(render(scene, view, options).fb.pixel(32, 32));
  EXPECT_NEAR(got.r, 0.5f * 1.1f + 0.4f, 1.5f / 255);
}

TEST(SceneShading, BoxWithoutNormalsHasFlatFaces) {
  // Computed normals split at the box's 90 degree edges, so under a directional light each face is one colour, the
  // one flat shading (face normals) gives it; smooth normals would shade each face as a gradient. The material has
  // no specular term, which would vary with the view direction across a face.
  Mesh m = cube();
  m.materials = {Material{"matte", glm::vec4(1.0f), glm::vec3(0.0f), 32, {}}};
  m.face_materials.assign(m.triangle_count(), 0);
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({1.6f, 2.2f, 3.4f});
  SceneOptions options;
  options.shading = Shading::blinn_phong;
  options.lights = {Light{Light::Kind::directional, {0.3f, 0.5f, 0.8f}, glm::vec3(1.0f), 1.0f}};
  options.ambient = glm::vec3(0.1f);
  const Frame lit = render(scene, view, options);
  options.shading = Shading::flat;
  const Frame flat = render(scene, view, options);

  struct Face {
    glm::vec3 center, u, v;
  };
  const Face visible[3] = {{{0, 0, 0.5f}, {1, 0, 0}, {0, 1, 0}},   // +z
                           {{0.5f, 0, 0}, {0, 0, 1}, {0, 1, 0}},   // +x
                           {{0, 0.5f, 0}, {1, 0, 0}, {0, 0, 1}}};  // +y
  std::vector<int> face_colors;
  for (const Face& face : visible) {
    const glm::vec3 n = glm::normalize(face.center);
    int lo = 255, hi = 0;
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j) {  // inset from the face's edges by 0.2, a few pixels
        const glm::vec2 p =
            project(view, face.center + 0.1f * (static_cast<float>(i) * face.u + static_cast<float>(j) * face.v));
        const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
        const glm::vec4 got = unpack_rgba8(lit.fb.pixel(x, y)), want = unpack_rgba8(flat.fb.pixel(x, y));
        EXPECT_NEAR(got.r, want.r, 1.5f / 255) << "face " << n.x << n.y << n.z << " at " << x << ", " << y;
        lo = std::min(lo, static_cast<int>(std::lround(got.r * 255)));
        hi = std::max(hi, static_cast<int>(std::lround(got.r * 255)));
      }
    EXPECT_LE(hi - lo, 1) << "face " << n.x << " " << n.y << " " << n.z;
    face_colors.push_back(lo);
  }
  // Three different shades, so the light really does tell the faces apart.
  EXPECT_EQ(std::set<int>(face_colors.begin(), face_colors.end()).size(), 3u);
}

TEST(SceneShading, DepthShadingUsesTheViewRange) {
  Mesh m;
  add_quad(m, 0.0f);
  add_quad(m, -1.0f, 4.0f, 4.0f);
  Scene scene;
  scene.add(instance(m));
  SceneOptions options;
  options.shading = Shading::depth;
  const Frame f = render(scene, make_view({0, 0, 3}, 1.0f, 5.0f), options);
  EXPECT_EQ(f.fb.pixel(32, 32), pack_rgba8({0.5f, 0.5f, 0.5f, 1}));    // distance 3
  EXPECT_EQ(f.fb.pixel(2, 32), pack_rgba8({0.25f, 0.25f, 0.25f, 1}));  // distance 4
}

TEST(SceneDepth, LinearDepthInvertsPerspectiveAndOrthographic) {
  Framebuffer fb(4, 3);
  const glm::mat4 projections[3] = {glm::perspective(glm::radians(50.0f), 4.0f / 3, 0.1f, 100.0f),
                                    glm::frustum(-0.05f, 0.12f, -0.03f, 0.06f, 0.1f, 50.0f),
                                    glm::ortho(-2.0f, 2.0f, -1.5f, 1.5f, 0.5f, 20.0f)};
  for (const glm::mat4& p : projections) {
    std::fill(fb.mutable_depth().begin(), fb.mutable_depth().end(), 1.0f);
    const float distances[3] = {0.7f, 7.0f, 17.0f};
    for (int k = 0; k < 3; ++k) {
      const glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -distances[k], 1.0f);
      fb.mutable_depth()[static_cast<std::size_t>(k) * 4 + 1] = clip.z / clip.w * 0.5f + 0.5f;
    }
    const std::vector<float> linear = linear_depth(fb, p);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(linear[static_cast<std::size_t>(k) * 4 + 1], distances[k], distances[k] * 1e-3f);
    EXPECT_EQ(linear[0], 0.0f);  // nothing drawn
  }
}

TEST(SceneDepth, LinearDepthOfARenderedQuad) {
  Mesh m;
  add_quad(m, -1.0f);
  Scene scene;
  scene.add(instance(m));
  const View view = make_view({0, 0, 3});
  const Frame f = render(scene, view, SceneOptions{});
  const std::vector<float> linear = linear_depth(f.fb, view.clip_from_view);
  EXPECT_NEAR(linear[32 * kSize + 32], 4.0f, 4e-3f);
  EXPECT_NEAR(linear[20 * kSize + 40], 4.0f, 4e-3f);
  EXPECT_EQ(linear[0], 0.0f);
}


}  // namespace
}  // namespace facet::scene_tests

namespace facet::scene_tests {
namespace {

// A small cloud on a sphere of radius 0.5, with or without outward normals, and a red quad behind it.
Mesh cloud_and_quad(bool normals) {
  Mesh m;
  for (int i = 0; i < 400; ++i) {
    const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / 400.0f, r = std::sqrt(1.0f - z * z);
    const float t = 2.39996f * static_cast<float>(i);
    const glm::vec3 p(r * std::cos(t), r * std::sin(t), z);
    m.positions.push_back(0.5f * p);
    if (normals) m.normals.push_back(p);
    m.colors.emplace_back(0.2f, 1.0f, 0.2f, 1.0f);
    m.points.push_back(static_cast<std::uint32_t>(i));
  }
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    m.positions.emplace_back(c.x, c.y, -1.0f);
    if (normals) m.normals.emplace_back(0, 0, 1);
    m.colors.emplace_back(1.0f, 0.0f, 0.0f, 1.0f);
  }
  m.indices = {base, base + 1, base + 2, base, base + 2, base + 3};
  return m;
}

// Every shading draws a mesh's points over its triangles, with or without normals (a point has no face: flat
// shading lights each point once, and a cloud without normals is drawn unlit).
TEST(ScenePoints, EveryShadingDrawsThePointsInFrontOfTheSurface) {
  const View view = make_view({0, 0, 3});
  for (const bool normals : {false, true})
    for (const Shading shading : {Shading::automatic, Shading::unlit, Shading::flat, Shading::gouraud, Shading::phong,
                                  Shading::blinn_phong, Shading::normals, Shading::depth}) {
      SCOPED_TRACE(std::string(normals ? "with" : "without") + " normals, shading " +
                   std::to_string(static_cast<int>(shading)));
      Scene scene;
      scene.add(instance(cloud_and_quad(normals)));
      SceneOptions options;
      options.shading = shading;
      options.point_size = 3.0f;
      const Frame frame = render(scene, view, options);
      // The cloud's centre pixel shows a point, nearer than the quad: its depth is below the quad's.
      const float centre_depth = frame.fb.depth_at(kSize / 2, kSize / 2);
      const float quad_depth = frame.fb.depth_at(2, 2);
      EXPECT_LT(centre_depth, quad_depth);
      if (shading == Shading::unlit || (!normals && shading != Shading::normals && shading != Shading::depth)) {
        // In their own colour, unlit.
        int green = 0;
        for (int y = 16; y < 48; ++y)
          for (int x = 16; x < 48; ++x) green += frame.fb.pixel(x, y) == pack_rgba8({0.2f, 1.0f, 0.2f, 1.0f});
        EXPECT_GT(green, 100);
      }
    }
}


// A cloud (points alone) is prepared in spatial order: its points, stored shuffled, come out with neighbours next to
// each other (a path through them in order is a fraction of the shuffled one), every point once with its own
// colour, and a point naming no vertex stays one. Its vertices get the default normal, with no crease normals.
TEST(ScenePoints, ACloudIsPreparedInSpatialOrder) {
  Mesh cloud;
  const int side = 40;
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        cloud.positions.emplace_back(x, y, z);
        cloud.colors.emplace_back(x / 64.0f, y / 64.0f, z / 64.0f, 1.0f);
      }
  const auto n = static_cast<std::uint32_t>(cloud.positions.size());
  for (std::uint32_t v = 0; v < n; ++v) cloud.points.push_back((v * 7919u) % n);  // a shuffle: 7919 is prime
  cloud.points.push_back(n + 3);                                                   // no such vertex
  const auto path = [](const std::vector<glm::vec3>& p) {
    double length = 0;
    for (std::size_t i = 1; i < p.size(); ++i) length += glm::length(p[i] - p[i - 1]);
    return length;
  };
  std::vector<glm::vec3> shuffled;
  for (std::size_t i = 0; i + 1 < cloud.points.size(); ++i) shuffled.push_back(cloud.positions[cloud.points[i]]);

  detail::TextureCache textures;
  const detail::PreparedMesh prepared = detail::prepare_mesh(cloud, textures);
  ASSERT_EQ(prepared.points.indices.size(), cloud.points.size());
  EXPECT_GE(prepared.points.indices.back(), prepared.vertices.size());  // still names no vertex, and comes last
  std::vector<glm::vec3> ordered;
  std::set<std::array<float, 3>> seen;
  for (std::size_t i = 0; i + 1 < prepared.points.indices.size(); ++i) {
    const MeshVertex& v = prepared.vertices.at(prepared.points.indices[i]);
    ordered.push_back(v.position);
    seen.insert({v.position.x, v.position.y, v.position.z});
    EXPECT_EQ(v.color, glm::vec4(v.position / 64.0f, 1.0f));
    EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
  }
  EXPECT_EQ(seen.size(), n);
  EXPECT_EQ(prepared.vertices.size(), n);
  EXPECT_LT(path(ordered), path(shuffled) / 4);  // 1.5 against 11.5 a step
}

}  // namespace
}  // namespace facet::scene_tests
