// fragment_non_const.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: a fragment() that is not const, so the pipeline could not call it.
// expect-error: facet shader rule: fragment() is a const member function
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/renderer.hpp"

struct BrokenShader {
  struct Vertex {
    glm::vec3 position;
  };
  struct Varyings {
    glm::vec3 normal;
  };
  static constexpr bool may_discard = false;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  glm::vec4 fragment(const facet::Fragment<Varyings>&) { return glm::vec4(1.0f); }
};
FACET_EXTERN_SHADER(BrokenShader);
