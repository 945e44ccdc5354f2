// bench_scenes.hpp - the `facet bench` scenes (BENCHMARK.md 8.1-8.3) and camera matrices (section 5), in float32.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bench/bench_shader.hpp"

namespace facet::bench {

inline constexpr float kBenchPointSize = 2.0f;  // pixels, facet render's default

struct BenchGeometry {
  std::vector<BenchVertex> vertices;
  std::vector<std::uint32_t> indices;  // 3 per triangle, in draw order; or 1 per point
  bool points = false;                 // a point cloud's: drawn as 2-pixel squares (kBenchPointSize)
  std::string name;                    // the JSON "scene" value, e.g. "sphere:224"
};

// sphere:N, 2N(N-1) triangles (8.1). Expects 3 <= n <= 4096.
BenchGeometry make_sphere(int n);

// quads:K:b2f / quads:K:f2b, 2K triangles (8.2). Expects 1 <= k <= 4096.
BenchGeometry make_quads(int k, bool front_to_back);

// mesh:<file name> (8.3): triangles in file order, normalised to the unit sphere, file normals or area-weighted
// smooth normals, file uvs or planar uvs. Throws InputError when the file cannot be loaded, has no triangles, has
// a non-finite position or all its vertices coincide.
BenchGeometry load_mesh_scene(const std::string& path);

// Column-major 4x4 product with the reference's summation order (k = 0..3), so matrices match glref bit for bit.
glm::mat4 multiply(const glm::mat4& a, const glm::mat4& b);

// P for a W x H target: 45 degree vertical field of view, near 0.1, far 100.
glm::mat4 projection_matrix(int width, int height);
// V: the eye at (0, 0, 3) looking down -Z.
glm::mat4 view_matrix();
// M(f) = R_y(0.6 + 0.02 f) * (R_x(-0.3) * S(scale)) for the sphere and mesh; identity for the quads.
glm::mat4 model_matrix(int frame, float scale, bool identity);

}  // namespace facet::bench
