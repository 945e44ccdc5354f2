// scenes.cpp - the sphere, the overdraw quads and a model file, built as the benchmark's scene contract defines them.
#include "scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace glref {

// A UV sphere of radius 1: n stacks from the +Y pole, n slices, the seam's vertices repeated; the pole rows keep
// only their non-degenerate triangle. Angles in float, as the contract computes them.
Scene make_sphere(int n) {
  Scene scene;
  scene.name = "sphere:" + std::to_string(n);
  const float pi = std::numbers::pi_v<float>;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float theta = pi * static_cast<float>(i) / static_cast<float>(n);
      const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(n);
      const float x = std::sin(theta) * std::cos(phi), y = std::cos(theta), z = std::sin(theta) * std::sin(phi);
      scene.vertices.push_back({{x, y, z},
                                {x, y, z},
                                {8.0f * static_cast<float>(j) / static_cast<float>(n),
                                 4.0f * static_cast<float>(i) / static_cast<float>(n)}});
    }
  const auto row = static_cast<std::uint32_t>(n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = static_cast<std::uint32_t>(i) * row + static_cast<std::uint32_t>(j), b = a + row;
      if (i != 0) scene.indices.insert(scene.indices.end(), {a, a + 1, b});
      if (i != n - 1) scene.indices.insert(scene.indices.end(), {a + 1, b + 1, b});
    }
  return scene;
}

// k camera-facing quads from z = 1.5 to z = -3, each about 95% of the view at its depth. Their offsets and texture
// shifts follow the depth rank, so both orders draw the same picture.
Scene make_quads(int k, bool front_to_back) {
  Scene scene;
  scene.name = "quads:" + std::to_string(k) + (front_to_back ? ":f2b" : ":b2f");
  scene.animated = false;
  const float kX[4] = {-1, 1, 1, -1}, kY[4] = {-1, -1, 1, 1}, kU[4] = {0, 1, 1, 0}, kV[4] = {0, 0, 1, 1};
  const float tan_half_fov = std::tan(std::numbers::pi_v<float> / 8.0f);
  for (int i = 0; i < k; ++i) {
    const int rank = front_to_back ? i : k - 1 - i;
    const float d = static_cast<float>(rank);
    const float z = 1.5f - 4.5f * d / static_cast<float>(std::max(1, k - 1));
    const float hh = 0.95f * (3.0f - z) * tan_half_fov, hw = hh * 1920.0f / 1080.0f;
    const float ox = 0.05f * hw * std::sin(1.3f * d), oy = 0.05f * hh * std::cos(0.7f * d);
    for (int c = 0; c < 4; ++c)
      scene.vertices.push_back({{kX[c] * hw + ox, kY[c] * hh + oy, z}, {0, 0, 1}, {kU[c] * 4 + 0.1f * d, kV[c] * 4}});
    const auto v = static_cast<std::uint32_t>(4 * i);
    scene.indices.insert(scene.indices.end(), {v, v + 1, v + 2, v, v + 2, v + 3});
  }
  return scene;
}

namespace {

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Area-weighted smooth normals: each triangle's unnormalized cross product summed at every corner that lies at
// bitwise the same position, then normalized ((0, 0, 1) where the sum vanishes).
void smooth_normals(Scene& scene) {
  using Key = std::array<std::uint32_t, 3>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return (std::size_t{k[0]} * 0x9E3779B97F4A7C15ull) ^ (std::size_t{k[1]} * 0xC2B2AE3D27D4EB4Full) ^ k[2];
    }
  };
  // Each vertex's position group: vertices at bitwise the same position share one sum.
  std::unordered_map<Key, std::uint32_t, Hash> groups;
  groups.reserve(scene.vertices.size());
  std::vector<std::uint32_t> group_of(scene.vertices.size());
  for (std::size_t v = 0; v < scene.vertices.size(); ++v) {
    Key k;
    std::memcpy(k.data(), scene.vertices[v].position, sizeof k);
    group_of[v] = groups.try_emplace(k, static_cast<std::uint32_t>(groups.size())).first->second;
  }
  std::vector<std::array<double, 3>> sums(groups.size(), {0.0, 0.0, 0.0});
  for (std::size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
    const float* p[3];
    for (int c = 0; c < 3; ++c) p[c] = scene.vertices[scene.indices[t + static_cast<std::size_t>(c)]].position;
    const double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (int c = 0; c < 3; ++c) {
      auto& sum = sums[group_of[scene.indices[t + static_cast<std::size_t>(c)]]];
      for (int a = 0; a < 3; ++a) sum[static_cast<std::size_t>(a)] += n[a];
    }
  }
  for (std::size_t v = 0; v < scene.vertices.size(); ++v) {
    const auto& s = sums[group_of[v]];
    const double length = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    float* normal = scene.vertices[v].normal;
    if (length > 0) {
      for (int a = 0; a < 3; ++a) normal[a] = static_cast<float>(s[static_cast<std::size_t>(a)] / length);
    } else {
      normal[0] = 0, normal[1] = 0, normal[2] = 1;
    }
  }
}

}  // namespace

// The file's triangles in order (points and lines dropped, node transforms applied), centred and scaled into the
// unit sphere; its normals where every vertex has a usable one, its uvs where they vary, else planar uvs.
Scene load_mesh(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* file = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                    aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!file) throw SceneError(path + ": " + importer.GetErrorString());
  const std::size_t slash = path.find_last_of('/');
  Scene scene;
  scene.name = "mesh:" + path.substr(slash == std::string::npos ? 0 : slash + 1);
  bool normals = true, uvs = true;
  for (unsigned m = 0; m < file->mNumMeshes; ++m) {
    const aiMesh& mesh = *file->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(scene.vertices.size());
    bool used = false;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (int c = 0; c < 3; ++c) scene.indices.push_back(base + face.mIndices[c]);
      used = true;
    }
    if (!used) continue;
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      Vertex v{};
      const aiVector3D& p = mesh.mVertices[i];
      if (!finite(p)) throw SceneError(path + ": a vertex position is not finite");
      v.position[0] = p.x, v.position[1] = p.y, v.position[2] = p.z;
      if (mesh.mNormals && finite(mesh.mNormals[i]) && mesh.mNormals[i].SquareLength() > 0) {
        v.normal[0] = mesh.mNormals[i].x, v.normal[1] = mesh.mNormals[i].y, v.normal[2] = mesh.mNormals[i].z;
      } else {
        normals = false;
      }
      if (mesh.mTextureCoords[0] && finite(mesh.mTextureCoords[0][i])) {
        v.uv[0] = mesh.mTextureCoords[0][i].x, v.uv[1] = mesh.mTextureCoords[0][i].y;
      } else {
        uvs = false;
      }
      scene.vertices.push_back(v);
    }
  }
  if (scene.indices.empty()) throw SceneError(path + ": no triangles");

  float lo[3], hi[3];
  for (int a = 0; a < 3; ++a) lo[a] = hi[a] = scene.vertices[0].position[a];
  for (const Vertex& v : scene.vertices)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v.position[a]), hi[a] = std::max(hi[a], v.position[a]);
  float centre[3], radius = 0;
  for (int a = 0; a < 3; ++a) centre[a] = (lo[a] + hi[a]) / 2;
  for (const Vertex& v : scene.vertices) {
    const float dx = v.position[0] - centre[0], dy = v.position[1] - centre[1], dz = v.position[2] - centre[2];
    radius = std::max(radius, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  if (!(radius > 0)) throw SceneError(path + ": all vertices coincide");
  for (Vertex& v : scene.vertices)
    for (int a = 0; a < 3; ++a) v.position[a] = (v.position[a] - centre[a]) / radius;

  if (!normals) smooth_normals(scene);
  float uv_lo[2] = {scene.vertices[0].uv[0], scene.vertices[0].uv[1]}, uv_hi[2] = {uv_lo[0], uv_lo[1]};
  for (const Vertex& v : scene.vertices)
    for (int a = 0; a < 2; ++a) uv_lo[a] = std::min(uv_lo[a], v.uv[a]), uv_hi[a] = std::max(uv_hi[a], v.uv[a]);
  if (!uvs || (uv_hi[0] - uv_lo[0] < 1e-6f && uv_hi[1] - uv_lo[1] < 1e-6f))
    for (Vertex& v : scene.vertices) {
      v.uv[0] = 4 * v.position[0];
      v.uv[1] = 4 * v.position[1] + 2 * v.position[2];
    }
  return scene;
}

}  // namespace glref
