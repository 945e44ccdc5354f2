// test_surface_buffers.cpp - the id pass, camera-space normals, face and instance ids from the loaders, .npy and .exr.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/primitives.hpp"
#include "facet/render_job.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/npy.hpp"
#include "support/scratch_dir.hpp"

namespace facet::surface_buffers_tests {
namespace {

namespace fs = std::filesystem;

const fs::path kBox = "/usr/share/assimp/models/OBJ/box.obj";

struct Frame {
  std::vector<float> depth;  // linear, 0 where empty
  SurfaceIds ids;
  std::vector<glm::vec3> normals;
};

// The colour pass's depth and the id pass's ids and normals of one scene and view.
Frame draw_buffers(Scene& scene, const View& view, const SceneOptions& options, int width, int height) {
  Renderer renderer(2);
  Framebuffer target(width, height), ids_target(width, height);
  renderer.clear(target);
  scene.render(renderer, target, view, options);
  renderer.finish(target);
  Frame frame{linear_depth(target, view.clip_from_view), scene.render_ids(renderer, ids_target, view, options), {}};
  frame.normals = scene.camera_normals(frame.ids, view);
  return frame;
}

// The unit box's faces are flat: the normal at a pixel is the face normal of the triangle the ids name.
TEST(SurfaceIds, NameTheTriangleSeenAndItsNormalEverywhereTheColourPassDrew) {
  const auto mesh = std::make_shared<Mesh>(load_model(kBox));
  Scene scene;
  scene.add(Instance{mesh, glm::mat4(1.0f)});
  for (const Projection projection : {Projection::perspective, Projection::isometric, Projection::oblique}) {
    CameraSpec spec;
    spec.projection = projection;
    spec.azimuth_degrees = 25.0f;
    spec.elevation_degrees = 30.0f;
    const int width = 80, height = 60;
    const View view = make_view(spec, {{0, 0, 0}, std::sqrt(0.75f)}, static_cast<float>(width) / height);
    const Frame frame = draw_buffers(scene, view, SceneOptions{}, width, height);
    int drawn = 0;
    for (std::size_t p = 0; p < frame.depth.size(); ++p) {
      const bool empty = frame.depth[p] == 0.0f;
      ASSERT_EQ(frame.ids.instance[p] == kNoSurface, empty) << "pixel " << p;
      ASSERT_EQ(frame.ids.triangle[p] == kNoSurface, empty) << "pixel " << p;
      if (empty) {
        EXPECT_EQ(frame.normals[p], glm::vec3(0.0f));
        continue;
      }
      ++drawn;
      ASSERT_EQ(frame.ids.instance[p], 0u);
      ASSERT_LT(frame.ids.triangle[p], mesh->triangle_count());
      const std::uint32_t* corner = &mesh->indices[3 * frame.ids.triangle[p]];
      const glm::mat3 view_from_world(view.view_from_world);
      const glm::vec3 a = view_from_world * mesh->positions[corner[0]],
                      b = view_from_world * mesh->positions[corner[1]],
                      c = view_from_world * mesh->positions[corner[2]];
      const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
      EXPECT_NEAR(glm::length(frame.normals[p]), 1.0f, 1e-5f);
      EXPECT_GT(glm::dot(frame.normals[p], face), 0.9999f) << "pixel " << p;
      // The box is closed: what is seen faces the camera (the oblique view sees the top and side edge-on in z).
      EXPECT_GT(frame.normals[p].z, -1e-4f) << "pixel " << p;
    }
    EXPECT_GT(drawn, width * height / 8);
  }
}

// Smooth normals are interpolated, not taken per face: across a sphere they turn with the surface.
TEST(SurfaceIds, NormalsOfACurvedSurfaceFollowIt) {
  const auto sphere = std::make_shared<Mesh>(make_uv_sphere(48, 96));
  Scene scene;
  scene.add(Instance{sphere, glm::mat4(1.0f)});
  const int size = 64;
  const View view = make_view(CameraSpec{}, framing_of(*sphere, "sphere"), 1.0f);
  const Frame frame = draw_buffers(scene, view, SceneOptions{}, size, size);
  const glm::vec3 center(view.view_from_world * glm::vec4(0, 0, 0, 1));
  const glm::mat4 view_from_clip = glm::inverse(view.clip_from_view);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * size + x;
      if (frame.depth[p] == 0.0f) continue;
      // The point seen, from depth: on a unit sphere its normal is its direction from the centre.
      const float ndc_x = 2.0f * (x + 0.5f) / size - 1.0f, ndc_y = 1.0f - 2.0f * (y + 0.5f) / size;
      const glm::vec4 far = view_from_clip * glm::vec4(ndc_x, ndc_y, 1.0f, 1.0f);
      const glm::vec3 ray = glm::vec3(far) / far.w;
      const glm::vec3 point = ray * (frame.depth[p] / -ray.z);
      EXPECT_GT(glm::dot(frame.normals[p], glm::normalize(point - center)), 0.998f) << x << "," << y;
    }
}

TEST(SurfaceIds, NameTheInstanceOfEachPixel) {
  const auto mesh = std::make_shared<Mesh>(load_model(kBox));
  Scene scene;
  scene.add(Instance{mesh, glm::translate(glm::mat4(1.0f), glm::vec3(-1.0f, 0, 0))});
  scene.add(Instance{mesh, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0))});
  CameraSpec spec;
  spec.position = glm::vec3(0.0f, 0.0f, 6.0f);
  const int width = 96, height = 48;
  const View view = make_view(spec, {{0, 0, 0}, 1.6f}, 2.0f);
  for (const bool painter : {false, true}) {
    SceneOptions options;
    options.painter = painter;
    const Frame frame = draw_buffers(scene, view, options, width, height);
    const std::size_t row = static_cast<std::size_t>(height / 2) * width;
    EXPECT_EQ(frame.ids.instance[row + width / 2 - width / 6], 0u);
    EXPECT_EQ(frame.ids.instance[row + width / 2 + width / 6], 1u);
    EXPECT_EQ(frame.ids.instance[row], kNoSurface);
  }
}

std::vector<std::uint32_t> ids_of(const Mesh& mesh, bool instances) {
  std::vector<std::uint32_t> out;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    out.push_back(instances ? mesh.instance_id(t) : mesh.face_id(t));
  return out;
}

// A polygon's triangles share its face number. A PLY face of two corners is dropped but keeps its number; OBJ
// numbers the `f` lines of three or more corners (the reader drops shorter ones as it parses).
TEST(FaceIds, NumberThePolygonsAsTheFileDoes) {
  const fs::path dir = test::scratch_dir("surface_buffers");
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
      "f 1 2 5\nf 1 2\nf 1 2 3 4\nf 2 5 3\n";
  const Mesh from_obj = load_model(test::write_file(dir, "faces.obj", obj));
  EXPECT_EQ(ids_of(from_obj, false), (std::vector<std::uint32_t>{0, 1, 1, 2}));
  EXPECT_EQ(ids_of(from_obj, true), (std::vector<std::uint32_t>{0, 0, 0, 0}));

  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n4 0 1 2 3\n2 0 1\n3 1 4 2\n5 0 1 4 2 3\n";
  EXPECT_EQ(ids_of(load_model(test::write_file(dir, "faces.ply", ply)), false),
            (std::vector<std::uint32_t>{0, 0, 2, 3, 3, 3}));

  // Triangles only: the ids are the triangle indices and take no memory.
  const Mesh triangles =
      load_model(test::write_file(dir, "triangles.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 3 2 1\n"));
  EXPECT_TRUE(triangles.face_ids.empty());
  EXPECT_EQ(ids_of(triangles, false), (std::vector<std::uint32_t>{0, 1}));
}

// Each glTF node that places a mesh is an instance, numbered as the file numbers its nodes.
TEST(FaceIds, GltfNodesAreTheInstances) {
  const fs::path dir = test::scratch_dir("surface_buffers");
  const float positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(sizeof positions + sizeof indices, '\0');
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
      R"("nodes":[{"children":[2,1]},{"mesh":0,"translation":[2,0,0]},{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],)"
      R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
      test::base64(buffer) + R"("}]})";
  const Mesh mesh = load_model(test::write_file(dir, "two_nodes.gltf", gltf));
  EXPECT_EQ(ids_of(mesh, true), (std::vector<std::uint32_t>{2, 2, 1, 1}));
  EXPECT_EQ(ids_of(mesh, false), (std::vector<std::uint32_t>{0, 1, 0, 1}));
}

TEST(FaceIds, ValidateRefusesTheReservedIdAndWrongSizes) {
  Mesh mesh = make_cube();
  mesh.face_ids.assign(mesh.triangle_count(), 0);
  EXPECT_NO_THROW(validate(mesh, "cube"));
  mesh.face_ids.back() = kNoSurface;
  EXPECT_THROW(validate(mesh, "cube"), InputError);
  mesh.face_ids.pop_back();
  EXPECT_THROW(validate(mesh, "cube"), InputError);
}

float as_float(std::uint32_t word) { return std::bit_cast<float>(word); }

// Depth, mask and ids describe each pixel's centre at any sample count: with 4 samples they are the 1-sample
// render's, bit for bit, where sample 0 (a quarter pixel off) would move every silhouette; and the colour image lines
// up with them (each pixel that the mask and its neighbours call empty shows the background).
TEST(Render, BuffersTakePixelCentresAtAnySampleCount) {
  const fs::path dir = test::scratch_dir("centre_buffers");
  const auto render_at = [&](int samples, const std::string& name) {
    RenderJob job;
    job.model = kBox;
    job.width = 61;
    job.height = 47;
    job.samples = samples;
    job.look.background = glm::vec3(0.0f, 0.0f, 1.0f);
    job.outputs = {.color = dir / (name + "c.png"),
                   .depth = dir / (name + "d.npy"),
                   .ids = dir / (name + "i.npy"),
                   .mask = dir / (name + "m.png")};
    Renderer renderer(2);
    render(job, renderer);
    return job.outputs;
  };
  const OutputSpec one = render_at(1, "one_"), four = render_at(4, "four_");
  EXPECT_EQ(test::read_npy(four.depth).words, test::read_npy(one.depth).words);
  EXPECT_EQ(test::read_npy(four.ids).words, test::read_npy(one.ids).words);
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(four.mask, w, h);
  EXPECT_EQ(mask, read_png(one.mask, w, h));
  const std::vector<std::uint8_t> color = read_png(four.color, w, h);
  int empty = 0, covered = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const auto at = [&](int dx, int dy) { return mask[4 * (static_cast<std::size_t>(y + dy) * w + x + dx)]; };
      const std::size_t p = 4 * (static_cast<std::size_t>(y) * w + x);
      const bool background = color[p] == 0 && color[p + 1] == 0 && color[p + 2] == 255;
      if (at(0, 0) == 0 && at(-1, 0) == 0 && at(1, 0) == 0 && at(0, -1) == 0 && at(0, 1) == 0) {
        EXPECT_TRUE(background) << x << "," << y;
        ++empty;
      } else if (at(0, 0) && at(-1, 0) && at(1, 0) && at(0, -1) && at(0, 1)) {
        EXPECT_FALSE(background) << x << "," << y;
        ++covered;
      }
    }
  EXPECT_GT(empty, 200);
  EXPECT_GT(covered, 200);
}

// What render() writes agrees: a pixel is empty in the mask, depth, normals and ids alike, or in none.
TEST(Render, EveryBufferAgreesOnWhereTheModelIs) {
  const fs::path dir = test::scratch_dir("surface_buffers");
  RenderJob job;
  job.model = kBox;
  job.width = 64;
  job.height = 48;
  job.outputs = {.color = dir / "c.png",
                 .depth = dir / "d.npy",
                 .normal = dir / "n.npy",
                 .ids = dir / "i.npy",
                 .mask = dir / "m.png"};
  Renderer renderer(2);
  render(job, renderer);
  const test::Npy depth = test::read_npy(dir / "d.npy"), normal = test::read_npy(dir / "n.npy"),
                  ids = test::read_npy(dir / "i.npy");
  EXPECT_NE(normal.header.find("'descr': '<f4', 'fortran_order': False, 'shape': (48, 64, 3)"), std::string::npos);
  EXPECT_NE(ids.header.find("'descr': '<u4', 'fortran_order': False, 'shape': (48, 64, 2)"), std::string::npos);
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(dir / "m.png", w, h);
  ASSERT_EQ(depth.words.size(), 64u * 48u);
  ASSERT_EQ(normal.words.size(), 3 * depth.words.size());
  ASSERT_EQ(ids.words.size(), 2 * depth.words.size());
  const Mesh box = load_model(kBox);
  int drawn = 0;
  for (std::size_t p = 0; p < depth.words.size(); ++p) {
    const bool empty = mask[4 * p] == 0;
    drawn += !empty;
    EXPECT_EQ(as_float(depth.words[p]) == 0.0f, empty) << p;
    const glm::vec3 n(as_float(normal.words[3 * p]), as_float(normal.words[3 * p + 1]),
                      as_float(normal.words[3 * p + 2]));
    EXPECT_EQ(n == glm::vec3(0.0f), empty) << p;
    EXPECT_EQ(ids.words[2 * p] == kNoSurface, empty) << p;
    EXPECT_EQ(ids.words[2 * p + 1] == kNoSurface, empty) << p;
    if (!empty) {
      EXPECT_LT(ids.words[2 * p + 1], box.triangle_count());
    }
  }
  EXPECT_GT(drawn, 300);

  // Lines are no surface: asking normals or ids of a wireframe writes nothing.
  const fs::path wire = dir / "wire";
  fs::create_directories(wire);
  job.look.wireframe = true;
  job.outputs = {.color = wire / "c.png", .ids = wire / "i.npy"};
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(wire));
}

// OpenEXR files hold the float values exactly, as Y, R G or R G B channels, ZIP-compressed; 41 rows make three
// chunks of up to 16, the last one short.
TEST(FloatImage, ExrHoldsTheValuesExactly) {
  const fs::path dir = test::scratch_dir("surface_buffers");
  const int width = 37, height = 41;
  for (const int channels : {1, 2, 3}) {
    std::vector<float> values(static_cast<std::size_t>(width) * height * channels);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = std::ldexp(static_cast<float>(i) + 0.1f, -3);
    const fs::path path = dir / ("values" + std::to_string(channels) + ".EXR");
    write_float_image(path, width, height, channels, values);
    Imf::InputFile file(path.c_str());
    EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
    const Imath::Box2i window = file.header().dataWindow();
    ASSERT_EQ(window.max.x - window.min.x + 1, width);
    ASSERT_EQ(window.max.y - window.min.y + 1, height);
    std::vector<float> read(values.size(), -1.0f);
    Imf::FrameBuffer frame;
    const char* names[] = {channels == 1 ? "Y" : "R", "G", "B"};
    const std::size_t pixel = sizeof(float) * static_cast<std::size_t>(channels);
    for (int c = 0; c < channels; ++c) {
      ASSERT_NE(file.header().channels().findChannel(names[c]), nullptr) << names[c];
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(read.data() + c), pixel, pixel * width));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    EXPECT_EQ(read, values);
  }
  EXPECT_THROW(write_float_image(dir / "four.exr", 1, 1, 4, std::vector<float>(4)), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir / "four.exr"));
}

}  // namespace
}  // namespace facet::surface_buffers_tests
