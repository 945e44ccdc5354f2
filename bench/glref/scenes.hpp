// scenes.hpp - the benchmark scenes as the OpenGL reference builds them, independently of facet's own code.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace glref {

// One vertex as the reference's vertex shader reads it: object-space position and normal, and a texture coordinate.
struct Vertex {
  float position[3];
  float normal[3];
  float uv[2];
};

struct Scene {
  std::string name;     // "sphere:N", "quads:K:b2f", "mesh:<file name>"
  bool animated = true;  // the sphere and meshes turn from frame to frame; the quads stay still
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise in front
};

// A scene the contract refuses (bad file, no triangles, non-finite positions): the message names the problem.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Scene make_sphere(int n);
Scene make_quads(int k, bool front_to_back);
Scene load_mesh(const std::string& path);  // through Assimp, fitted into the unit sphere

}  // namespace glref
