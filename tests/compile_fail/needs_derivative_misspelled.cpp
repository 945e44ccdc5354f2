// needs_derivative_misspelled.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: needs_derivative for needs_derivatives, which would leave ddx/ddy zero.
// expect-error: facet shader rule: needs_derivative is not a shader hook; did you mean needs_derivatives?
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/renderer.hpp"

struct BrokenShader {
  struct Vertex {
    glm::vec3 position;
  };
  struct Varyings {
    glm::vec2 uv;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivative = true;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  glm::vec4 fragment(const facet::Fragment<Varyings>&) const { return glm::vec4(1.0f); }
};
FACET_EXTERN_SHADER(BrokenShader);
