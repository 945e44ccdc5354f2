// setup.hpp - primitive assembly, clipping, culling, fixed-point setup and binning of one chunk of primitives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/render_state.hpp"
#include "facet/detail/binning.hpp"
#include "facet/detail/clip.hpp"
#include "facet/detail/triangle_setup.hpp"

namespace facet::detail {

struct SetupInput {
  const glm::vec4* clip;                  // post-transform positions, or nullptr: ask clip_position
  ClipPositionFn clip_position;
  const void* clip_source;                // what clip_position reads
  const ProjectedVertex* projected;       // the same, projected and snapped (triangles only)
  std::size_t vertex_count;
  std::span<const std::uint32_t> indices;  // 3 per triangle or 2 per line
  const std::uint32_t* order;              // primitive permutation (painter's algorithm) or nullptr
  std::size_t first, count;                // primitives of this chunk, in draw order
  int width, height, tiles_x;
  CullMode cull;
  float line_width;
};

void setup_triangles(const SetupInput& input, SetupChunk& out);
void setup_lines(const SetupInput& input, SetupChunk& out);

// Depth key of every triangle for the painter's algorithm: the mean NDC depth of its corners (larger is farther).
void setup_depth_keys(const glm::vec4* clip, std::size_t vertex_count, std::span<const std::uint32_t> indices,
                      std::span<float> keys);

}  // namespace facet::detail
