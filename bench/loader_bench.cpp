// loader_bench.cpp - native STL and PLY loading against Assimp reading the same files, in bytes of file per second.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "facet/mesh.hpp"
#include "facet/model_io.hpp"
#include "facet/primitives.hpp"

namespace {

namespace fs = std::filesystem;
using facet::Mesh;

// A dense torus (about 200,000 triangles): large enough that per-file overheads do not count.
const Mesh& model() {
  static const Mesh mesh = facet::make_torus(1.0f, 0.35f, 500, 200);
  return mesh;
}

void put_float(std::string& out, float v) {
  char bytes[4];
  std::memcpy(bytes, &v, 4);
  out.append(bytes, 4);
}

std::string binary_stl(const Mesh& m) {
  std::string out(80, ' ');
  const auto triangles = static_cast<std::uint32_t>(m.triangle_count());
  out.append(reinterpret_cast<const char*>(&triangles), 4);
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) put_float(out, 0.0f);  // normal: readers recompute it
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put_float(out, m.positions[m.indices[3 * t + c]][k]);
    out.append(2, '\0');
  }
  return out;
}

std::string ascii_stl(const Mesh& m) {
  std::string out = "solid torus\n";
  char line[160];
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    out += " facet normal 0 0 0\n  outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const glm::vec3& p = m.positions[m.indices[3 * t + c]];
      std::snprintf(line, sizeof line, "   vertex %.7g %.7g %.7g\n", p.x, p.y, p.z);
      out += line;
    }
    out += "  endloop\n endfacet\n";
  }
  return out + "endsolid torus\n";
}

std::string ply(const Mesh& m, bool binary) {
  std::string out = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") +
                    " 1.0\nelement vertex " + std::to_string(m.vertex_count()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(m.triangle_count()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  char line[160];
  for (const glm::vec3& p : m.positions) {
    if (binary) {
      for (int k = 0; k < 3; ++k) put_float(out, p[k]);
    } else {
      std::snprintf(line, sizeof line, "%.7g %.7g %.7g\n", p.x, p.y, p.z);
      out += line;
    }
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    if (binary) {
      out += '\3';
      out.append(reinterpret_cast<const char*>(&m.indices[3 * t]), 12);
    } else {
      std::snprintf(line, sizeof line, "3 %u %u %u\n", m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
      out += line;
    }
  }
  return out;
}

// The file of one format, written once per process into the temporary folder.
fs::path file(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("facet_loader_bench_" + name);
  static std::vector<std::string> written;
  if (std::find(written.begin(), written.end(), name) == written.end()) {
    const std::string data = name == "binary.stl" ? binary_stl(model())
                             : name == "ascii.stl" ? ascii_stl(model())
                                                   : ply(model(), name == "binary.ply");
    std::ofstream(path, std::ios::binary) << data;
    written.push_back(name);
  }
  return path;
}

void BM_FacetLoad(benchmark::State& state, const std::string& name) {
  const fs::path path = file(name);
  for (auto _ : state) benchmark::DoNotOptimize(facet::load_model(path).indices.data());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fs::file_size(path)));
}

// Assimp reading the same file with the one post-process a renderer needs from it (triangles).
void BM_AssimpLoad(benchmark::State& state, const std::string& name) {
  const fs::path path = file(name);
  for (auto _ : state) {
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate);
    if (!scene || scene->mNumMeshes == 0) state.SkipWithError("Assimp could not read the file");
    benchmark::DoNotOptimize(scene);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(fs::file_size(path)));
}

}  // namespace

BENCHMARK_CAPTURE(BM_FacetLoad, binary_stl, std::string("binary.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssimpLoad, binary_stl, std::string("binary.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FacetLoad, ascii_stl, std::string("ascii.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssimpLoad, ascii_stl, std::string("ascii.stl"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FacetLoad, binary_ply, std::string("binary.ply"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssimpLoad, binary_ply, std::string("binary.ply"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FacetLoad, ascii_ply, std::string("ascii.ply"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_AssimpLoad, ascii_ply, std::string("ascii.ply"))->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
