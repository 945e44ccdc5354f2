// gltf_square.hpp - a small glTF file for loader and scene tests: a 2 x 2 square and whatever nodes a test adds.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

#include "support/base64.hpp"

namespace facet::test {

// A 2 x 2 square at z = 0, facing +z, placed by node 0; `nodes` (JSON objects, comma-separated, `node_count` of
// them) follow it in the scene. `top_level` adds members to the file's object (",\"cameras\":[...]"); `material`,
// if given, is the square's material.
inline std::string square_gltf(const std::string& nodes, int node_count, const std::string& top_level,
                               const std::string& material = "") {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(sizeof positions + sizeof indices, '\0');
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
  std::string scene = "0";
  for (int i = 1; i <= node_count; ++i) scene += "," + std::to_string(i);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + scene + R"(]}],)" +
         R"("nodes":[{"mesh":0})" + (nodes.empty() ? std::string() : "," + nodes) + "]" + top_level +
         (material.empty() ? std::string() : R"(,"materials":[)" + material + "]") +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)" +
         (material.empty() ? std::string() : R"(,"material":0)") +
         R"(}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],)"
         R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
         base64(buffer) + R"("}]})";
}

}  // namespace facet::test
