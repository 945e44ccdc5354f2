// draw_helpers.hpp - one-call drawing of test meshes with the fast renderer or the reference rasterizer.
#pragma once

#include <span>
#include <vector>

#include "facet/renderer.hpp"
#include "support/reference_rasterizer.hpp"
#include "support/scenes.hpp"
#include "support/test_shaders.hpp"

namespace facet::test {

inline std::vector<ColorShader::Vertex> color_vertices(const ClipMesh& m) {
  std::vector<ColorShader::Vertex> v;
  for (std::size_t i = 0; i < m.clip.size(); ++i) v.push_back({m.clip[i], m.color[i]});
  return v;
}

// How many times each pixel is shaded when `m` is drawn with `state` (depth test off unless the state says so).
// Counting invocations is a side effect, so shading is immediate: deferred shading would shade each pixel once.
inline std::vector<int> coverage_counts(const ClipMesh& m, int width, int height, RenderState state, int threads = 2,
                                        bool reference_path = false) {
  state.defer_shading = false;
  std::vector<int> counts(static_cast<std::size_t>(width) * height, 0);
  std::vector<CountingShader::Vertex> vertices;
  for (const glm::vec4& c : m.clip) vertices.push_back({c});
  Framebuffer fb(width, height);
  const CountingShader shader{&counts, width};
  if (reference_path) {
    reference::draw(fb, shader, std::span<const CountingShader::Vertex>(vertices), m.indices, state);
  } else {
    Renderer renderer(threads);
    renderer.draw(fb, shader, std::span<const CountingShader::Vertex>(vertices), m.indices, state);
    renderer.finish(fb);
  }
  return counts;
}

inline Framebuffer render_colors(const ClipMesh& m, int width, int height, const RenderState& state, int threads,
                                 bool reference_path = false) {
  Framebuffer fb(width, height);
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  const ColorShader shader;
  if (reference_path) {
    reference::clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    reference::draw(fb, shader, std::span<const ColorShader::Vertex>(vertices), m.indices, state);
  } else {
    Renderer renderer(threads);
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    renderer.draw(fb, shader, std::span<const ColorShader::Vertex>(vertices), m.indices, state);
    renderer.finish(fb);
  }
  return fb;
}

inline RenderState no_depth_no_cull() {
  RenderState s;
  s.cull = CullMode::none;
  s.depth_test = false;
  return s;
}

}  // namespace facet::test
