// bench_scenes.cpp - scene geometry and camera of `facet bench`, with the reference's float32 arithmetic.
#include "bench/bench_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>

#include "facet/error.hpp"
#include "facet/mesh.hpp"
#include "facet/model_io.hpp"

namespace facet::bench {
namespace {

// glref's float constant for pi; the angles below are formed from it exactly as glref forms them.
constexpr float kPi = 3.14159265358979f;

// Area-weighted smooth normals (8.3): each vertex gets the normalised sum of the unnormalised face normals of all
// triangles with a corner at exactly its position (bitwise-equal coordinates), or (0, 0, 1) if the sum is zero.
// Triangles are summed in index order and corners in order, as glref does, so the float sums agree too.
void smooth_normals(BenchGeometry& g) {
  auto& v = g.vertices;
  const auto less = [&](std::uint32_t a, std::uint32_t b) {
    const float* pa = &v[a].pos.x;
    const float* pb = &v[b].pos.x;
    return std::lexicographical_compare(pa, pa + 3, pb, pb + 3);
  };
  std::vector<std::uint32_t> order(v.size()), group(v.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), less);
  std::uint32_t groups = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
    group[order[i]] = (i > 0 && !less(order[i - 1], order[i])) ? groups - 1 : groups++;
  std::vector<glm::vec3> sum(groups, glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < g.indices.size(); t += 3) {
    const glm::vec3 p0 = v[g.indices[t]].pos, p1 = v[g.indices[t + 1]].pos, p2 = v[g.indices[t + 2]].pos;
    const glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
    const glm::vec3 n(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    for (int c = 0; c < 3; ++c) sum[group[g.indices[t + c]]] += n;
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    const glm::vec3 s = sum[group[i]];
    const float len = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    v[i].normal = len > 0.0f ? s / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
}

}  // namespace

BenchGeometry make_sphere(int n) {
  BenchGeometry g;
  const std::size_t side = static_cast<std::size_t>(n) + 1;
  g.vertices.reserve(side * side);
  for (int i = 0; i <= n; ++i) {  // stacks, from the +Y pole (i = 0) to the -Y pole (i = n)
    const float theta = kPi * static_cast<float>(i) / static_cast<float>(n);
    for (int j = 0; j <= n; ++j) {  // slices; j = n repeats j = 0 with u = 8
      const float phi = 2.0f * kPi * static_cast<float>(j) / static_cast<float>(n);
      const glm::vec3 normal(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const glm::vec2 uv(8.0f * static_cast<float>(j) / static_cast<float>(n),
                         4.0f * static_cast<float>(i) / static_cast<float>(n));
      g.vertices.push_back({normal, normal, uv});
    }
  }
  g.indices.reserve(static_cast<std::size_t>(n) * (n - 1) * 6);
  const auto stride = static_cast<std::uint32_t>(side);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {  // counter-clockwise seen from outside; pole rows keep one triangle per cell
      const std::uint32_t a = static_cast<std::uint32_t>(i) * stride + static_cast<std::uint32_t>(j), b = a + stride;
      if (i != 0) g.indices.insert(g.indices.end(), {a, a + 1, b});
      if (i != n - 1) g.indices.insert(g.indices.end(), {a + 1, b + 1, b});
    }
  g.name = "sphere:" + std::to_string(n);
  return g;
}

BenchGeometry make_quads(int k, bool front_to_back) {
  BenchGeometry g;
  // The aspect is 16:9 whatever the target size, so the geometry never depends on --resolution.
  const float tan_half_fovy = std::tan(45.0f * kPi / 180.0f / 2.0f), aspect = 1920.0f / 1080.0f, eye_z = 3.0f;
  const float xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1}, us[4] = {0, 1, 1, 0}, vs[4] = {0, 0, 1, 1};
  for (int i = 0; i < k; ++i) {                      // i is the draw order
    const int rank = front_to_back ? i : k - 1 - i;  // depth rank, 0 = nearest
    const float d = static_cast<float>(rank);
    const float z = 1.5f - 4.5f * d / static_cast<float>(std::max(1, k - 1));
    const float hh = 0.95f * (eye_z - z) * tan_half_fovy, hw = hh * aspect;
    // Offsets follow the depth rank, so both orders draw the same picture.
    const float ox = 0.05f * hw * std::sin(d * 1.3f), oy = 0.05f * hh * std::cos(d * 0.7f);
    const auto base = static_cast<std::uint32_t>(g.vertices.size());
    for (int c = 0; c < 4; ++c)
      g.vertices.push_back({{xs[c] * hw + ox, ys[c] * hh + oy, z}, {0, 0, 1}, {us[c] * 4 + 0.1f * d, vs[c] * 4}});
    g.indices.insert(g.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  g.name = "quads:" + std::to_string(k) + ":" + (front_to_back ? "f2b" : "b2f");
  return g;
}

BenchGeometry load_mesh_scene(const std::string& path) {
  const Mesh mesh = load_model(path);
  // A point cloud (a file with points and no triangles) is drawn as points, a facet extension of the contract.
  const bool points = mesh.indices.size() < 3 && !mesh.points.empty();
  if (mesh.indices.size() < 3 && !points) throw InputError(path, "the mesh has no triangles");

  // Keep only vertices that a triangle references, renumbered in order of first use: the reference (assimp) only
  // has face corners, so unreferenced positions must not widen the bounds below.
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(mesh.positions.size(), kUnused);
  std::vector<std::uint32_t> source;
  BenchGeometry g;
  const auto use = [&](std::uint32_t index) {
    if (remap[index] == kUnused) {
      remap[index] = static_cast<std::uint32_t>(source.size());
      source.push_back(index);
    }
    g.indices.push_back(remap[index]);
  };
  g.indices.reserve(mesh.indices.size() - mesh.indices.size() % 3);
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
    for (std::size_t c = 0; c < 3; ++c) use(mesh.indices[i + c]);
  if (points)
    for (const std::uint32_t index : mesh.points) use(index);
  g.points = points;

  bool file_normals = mesh.normals.size() == mesh.positions.size();
  bool file_uvs = mesh.uvs.size() == mesh.positions.size();
  g.vertices.reserve(source.size());
  for (const std::uint32_t s : source) {
    BenchVertex v{mesh.positions[s], glm::vec3(0.0f), glm::vec2(0.0f)};
    if (!std::isfinite(v.pos.x) || !std::isfinite(v.pos.y) || !std::isfinite(v.pos.z))
      throw InputError(path, "the mesh has a non-finite vertex position");
    if (file_normals) {
      v.normal = mesh.normals[s];
      file_normals = std::isfinite(v.normal.x) && std::isfinite(v.normal.y) && std::isfinite(v.normal.z) &&
                     v.normal.x * v.normal.x + v.normal.y * v.normal.y + v.normal.z * v.normal.z > 0.0f;
    }
    if (file_uvs) {
      v.uv = mesh.uvs[s];
      file_uvs = std::isfinite(v.uv.x) && std::isfinite(v.uv.y);
    }
    g.vertices.push_back(v);
  }

  // Normalise: bounding-box centre to the origin, the farthest vertex from it at distance 1.
  glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
  for (const BenchVertex& v : g.vertices) {
    lo = glm::min(lo, v.pos);
    hi = glm::max(hi, v.pos);
  }
  const glm::vec3 centre = 0.5f * (lo + hi);
  float r2 = 0.0f;
  for (const BenchVertex& v : g.vertices) {
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k) d2 += (v.pos[k] - centre[k]) * (v.pos[k] - centre[k]);
    r2 = std::max(r2, d2);
  }
  const float radius = std::sqrt(r2);
  if (!(radius > 0.0f) || !std::isfinite(radius))
    throw InputError(path, "the mesh is degenerate (all its vertices coincide)");
  for (BenchVertex& v : g.vertices) v.pos = (v.pos - centre) / radius;

  if (!file_normals && !points) smooth_normals(g);
  // A cloud without normals faces the camera.
  if (!file_normals && points)
    for (BenchVertex& v : g.vertices) v.normal = glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec2 uv_lo(std::numeric_limits<float>::infinity()), uv_hi(-std::numeric_limits<float>::infinity());
  for (const BenchVertex& v : g.vertices) {
    uv_lo = glm::min(uv_lo, v.uv);
    uv_hi = glm::max(uv_hi, v.uv);
  }
  if (!file_uvs || (uv_hi.x - uv_lo.x < 1e-6f && uv_hi.y - uv_lo.y < 1e-6f))
    for (BenchVertex& v : g.vertices) v.uv = {4.0f * v.pos.x, 4.0f * v.pos.y + 2.0f * v.pos.z};

  g.name = "mesh:" + path.substr(path.find_last_of('/') + 1);
  return g;
}

glm::mat4 multiply(const glm::mat4& a, const glm::mat4& b) {
  glm::mat4 r(0.0f);
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[k][row] * b[c][k];
      r[c][row] = s;
    }
  return r;
}

glm::mat4 projection_matrix(int width, int height) {
  const float fovy = 45.0f * kPi / 180.0f, aspect = static_cast<float>(width) / static_cast<float>(height);
  const float n = 0.1f, f = 100.0f, t = 1.0f / std::tan(fovy / 2.0f);
  glm::mat4 p(1.0f);
  p[0][0] = t / aspect;
  p[1][1] = t;
  p[2][2] = (f + n) / (n - f);
  p[2][3] = -1.0f;
  p[3][2] = 2.0f * f * n / (n - f);
  p[3][3] = 0.0f;
  return p;
}

glm::mat4 view_matrix() {
  glm::mat4 v(1.0f);
  v[3][2] = -3.0f;
  return v;
}

glm::mat4 model_matrix(int frame, float scale, bool identity) {
  if (identity) return glm::mat4(1.0f);
  const float ay = 0.6f + 0.02f * static_cast<float>(frame), ax = -0.3f;
  glm::mat4 ry(1.0f), rx(1.0f), s(1.0f);
  ry[0][0] = ry[2][2] = std::cos(ay);
  ry[2][0] = std::sin(ay);
  ry[0][2] = -std::sin(ay);
  rx[1][1] = rx[2][2] = std::cos(ax);
  rx[2][1] = -std::sin(ax);
  rx[1][2] = std::sin(ax);
  s[0][0] = s[1][1] = s[2][2] = scale;
  return multiply(ry, multiply(rx, s));
}

}  // namespace facet::bench
