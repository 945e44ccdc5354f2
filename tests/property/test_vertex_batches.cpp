// test_vertex_batches.cpp - large draws shade each batch's band of vertices: same image, bounded post-transform memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

constexpr int kWidth = 193, kHeight = 131;

// Exactly two setup batches of triangles, with rows of vertices in index order, as meshes from grids, strips and
// optimisers have them: each batch references kRowsPerBatch + 1 rows of vertices, and the two share one row.
constexpr int kCells = 512;
constexpr std::size_t kBatch = detail::kSetupChunk * detail::kChunksPerBatch;
constexpr std::size_t kRowsPerBatch = kBatch / (2 * kCells);
static_assert(kBatch % (2 * kCells) == 0);
constexpr std::size_t kBand = (kRowsPerBatch + 1) * (kCells + 1);
ClipMesh large_grid() { return jittered_grid(kCells, static_cast<int>(2 * kRowsPerBatch), 23, true); }

struct Drawn {
  Framebuffer image{kWidth, kHeight};
  DrawStats stats;
};

// Scaled past the frustum so that triangles of both batches cross it and are clipped.
Drawn draw(const ClipMesh& m, int threads) {
  Drawn out;
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  ColorShader shader;
  shader.clip_from_object = glm::scale(glm::mat4(1.0f), glm::vec3(1.3f, 1.2f, 1.0f));
  Renderer renderer(threads);
  renderer.clear(out.image, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
  renderer.draw(out.image, shader, std::span<const ColorShader::Vertex>(vertices), m.indices, no_depth_no_cull());
  renderer.finish(out.image);
  out.stats = renderer.last_stats();
  return out;
}

// The same mesh with its vertex array permuted and the indices remapped: identical triangles, but each batch
// now references vertices from all over the array.
ClipMesh shuffled_vertices(const ClipMesh& m) {
  std::vector<std::uint32_t> new_index(m.clip.size());
  std::iota(new_index.begin(), new_index.end(), 0u);
  std::shuffle(new_index.begin(), new_index.end(), std::mt19937(5));
  ClipMesh s;
  s.clip.resize(m.clip.size());
  s.color.resize(m.color.size());
  for (std::size_t i = 0; i < m.clip.size(); ++i) {
    s.clip[new_index[i]] = m.clip[i];
    s.color[new_index[i]] = m.color[i];
  }
  for (const std::uint32_t i : m.indices) s.indices.push_back(new_index[i]);
  return s;
}

bool same_pixels(const Framebuffer& a, const Framebuffer& b) {
  return std::equal(a.color().begin(), a.color().end(), b.color().begin());
}

TEST(VertexBatches, CoherentMeshHoldsOneBandAtATime) {
  const ClipMesh grid = large_grid();
  const Drawn banded = draw(grid, 2);
  const std::size_t n = grid.clip.size();
  EXPECT_GT(banded.stats.clipped, 0u);
  EXPECT_EQ(banded.stats.primitives, 2 * kBatch);
  EXPECT_EQ(banded.stats.vertices_held, kBand);
  EXPECT_EQ(banded.stats.vertices_shaded, n + kCells + 1);  // the shared row twice
}

TEST(VertexBatches, ImageDoesNotDependOnVertexOrderOrThreads) {
  const ClipMesh grid = large_grid();
  const Drawn banded = draw(grid, 2);
  const Drawn whole = draw(shuffled_vertices(grid), 3);
  // A shuffled order would need every vertex in every batch, so the whole span is shaded once instead.
  EXPECT_EQ(whole.stats.vertices_held, grid.clip.size());
  EXPECT_EQ(whole.stats.vertices_shaded, grid.clip.size());
  EXPECT_EQ(whole.stats.binned, banded.stats.binned);
  EXPECT_TRUE(same_pixels(banded.image, whole.image));
  EXPECT_TRUE(same_pixels(banded.image, draw(grid, 1).image));
}

// A last part shorter than a batch joins the batch before it: one and a half batches are drawn as one, so every
// vertex is shaded once and held at once, and the image is that of any other cut.
TEST(VertexBatches, ShortLastPartJoinsThePreviousBatch) {
  const ClipMesh grid = jittered_grid(kCells, static_cast<int>(3 * kRowsPerBatch / 2), 31, true);
  const Drawn joined = draw(grid, 2);
  EXPECT_EQ(joined.stats.primitives, 3 * kBatch / 2);
  EXPECT_EQ(joined.stats.vertices_shaded, grid.clip.size());
  EXPECT_EQ(joined.stats.vertices_held, grid.clip.size());
  EXPECT_TRUE(same_pixels(joined.image, draw(grid, 1).image));
  EXPECT_TRUE(same_pixels(joined.image, draw(grid, 3).image));
  EXPECT_EQ(coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 2, false),
            coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 1, true));
}

TEST(VertexBatches, CoverageEqualsReference) {
  const ClipMesh grid = large_grid();
  const std::vector<int> fast = coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 2, false);
  const std::vector<int> slow = coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 1, true);
  EXPECT_EQ(fast, slow);
}

// A draw of fewer than 8 full chunks is set up in 8 smaller ones (at least kMinSetupChunk primitives each), so that
// threads share it; the chunks are walked in order, so the image is that of any other cut.
TEST(SetupChunks, SmallDrawsAreCutIntoSmallerChunks) {
  EXPECT_EQ(detail::setup_chunk_size(1), detail::kMinSetupChunk);
  EXPECT_EQ(detail::setup_chunk_size(3732), detail::kMinSetupChunk);
  EXPECT_EQ(detail::setup_chunk_size(8 * 1000), 1000u);
  EXPECT_EQ(detail::setup_chunk_size(8 * detail::kSetupChunk), detail::kSetupChunk);
  EXPECT_EQ(detail::setup_chunk_size(kBatch), detail::kSetupChunk);

  const ClipMesh grid = jittered_grid(40, 40, 29, true);  // 3,200 triangles: 7 chunks
  ASSERT_GT(grid.indices.size() / 3, 6 * detail::kMinSetupChunk);
  const Drawn one = draw(grid, 1);
  EXPECT_EQ(one.stats.primitives, grid.indices.size() / 3);
  EXPECT_TRUE(same_pixels(one.image, draw(grid, 2).image));
  EXPECT_TRUE(same_pixels(one.image, draw(grid, 3).image));
  EXPECT_EQ(coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 3, false),
            coverage_counts(grid, kWidth, kHeight, no_depth_no_cull(), 1, true));
}

TEST(VertexBatches, OutOfRangeIndicesDoNotWidenTheBand) {
  ClipMesh grid = large_grid();
  const std::size_t n = grid.clip.size();
  const Drawn clean = draw(grid, 2);
  // Invalid triangles in both batches: skipped, and they must not stretch a batch's band to the whole mesh.
  for (const std::size_t at : {std::size_t{3000}, grid.indices.size() - 3000}) {
    const std::uint32_t bad = 0xfffffff0u;
    grid.indices.insert(grid.indices.begin() + static_cast<std::ptrdiff_t>(at), {bad, bad, bad});
  }
  const Drawn dirty = draw(grid, 2);
  EXPECT_EQ(dirty.stats.invalid, 2u);
  EXPECT_LE(dirty.stats.vertices_held, kBand + kCells + 1);  // the batches now split one row later
  EXPECT_LT(dirty.stats.vertices_shaded, n + n / 10);
  EXPECT_TRUE(same_pixels(clean.image, dirty.image));
}

}  // namespace
}  // namespace facet::test
