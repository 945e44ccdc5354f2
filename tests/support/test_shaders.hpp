// test_shaders.hpp - small shaders the tests draw with: flat colour, per-vertex colour, coverage counting, uv checker.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "facet/renderer.hpp"
#include "facet/shader.hpp"

namespace facet::test {

// Positions already in clip space (w = 1 unless given), one colour per vertex.
struct ColorShader {
  struct Vertex {
    glm::vec4 clip;
    glm::vec3 color;
  };
  struct Varyings {
    glm::vec3 color;
  };
  static constexpr bool may_discard = false;
  glm::mat4 clip_from_object{1.0f};
  VertexOut<Varyings> vertex(const Vertex& v) const { return {clip_from_object * v.clip, {v.color}}; }
  glm::vec4 fragment(const Fragment<Varyings>& f) const { return glm::vec4(f.varyings.color, 1.0f); }
};

// ColorShader's colours at half opacity: with alpha blending, a sample drawn twice shows it.
struct TranslucentShader : ColorShader {
  glm::vec4 fragment(const Fragment<Varyings>& f) const { return glm::vec4(f.varyings.color, 0.5f); }
};

// Counts how often each pixel is shaded: fragment() has a side effect through a uniform pointer, which is safe
// because one thread owns each pixel.
struct CountingShader {
  struct Vertex {
    glm::vec4 clip;
  };
  struct Varyings {
    float unused;
  };
  static constexpr bool may_discard = false;
  std::vector<int>* counts;
  int width;
  VertexOut<Varyings> vertex(const Vertex& v) const { return {v.clip, {0.0f}}; }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    ++(*counts)[static_cast<std::size_t>(f.screen.y) * width + static_cast<std::size_t>(f.screen.x)];
    return glm::vec4(1.0f);
  }
};

// A world-space uv mapped to a checkerboard of `cells` cells per unit: black or white.
struct CheckerShader {
  struct Vertex {
    glm::vec3 position;
    glm::vec2 uv;
  };
  struct Varyings {
    glm::vec2 uv;
  };
  static constexpr bool may_discard = false;
  glm::mat4 clip_from_object{1.0f};
  bool affine = false;  // pre-divide by w so interpolation is linear in screen space (wrong on purpose)
  float cells = 8.0f;
  VertexOut<Varyings> vertex(const Vertex& v) const {
    glm::vec4 clip = clip_from_object * glm::vec4(v.position, 1.0f);
    if (affine) clip /= clip.w;
    return {clip, {v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const int parity = (static_cast<int>(std::floor(f.varyings.uv.x * cells)) +
                        static_cast<int>(std::floor(f.varyings.uv.y * cells))) &
                       1;
    return parity ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  }
};

}  // namespace facet::test

// Most tests draw with these: compiled once, in test_shaders.cpp.
FACET_EXTERN_SHADER(facet::test::ColorShader);
FACET_EXTERN_SHADER(facet::test::TranslucentShader);
FACET_EXTERN_SHADER(facet::test::CountingShader);
