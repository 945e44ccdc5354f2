// needs_derivatives_not_static.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: needs_derivatives as a per-object bool rather than a static constexpr one.
// expect-error: facet shader rule: needs_derivatives is a static constexpr bool
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
  bool needs_derivatives = true;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  glm::vec4 fragment(const facet::Fragment<Varyings>&) const { return glm::vec4(1.0f); }
};
FACET_EXTERN_SHADER(BrokenShader);
