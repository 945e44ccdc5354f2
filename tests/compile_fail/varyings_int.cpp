// varyings_int.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: an int in Varyings, which interpolation would blend as float bits.
// expect-error: facet shader rule: Varyings holds only float, glm::vec2, glm::vec3 and glm::vec4 members
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
    int material;
  };
  static constexpr bool may_discard = false;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  glm::vec4 fragment(const facet::Fragment<Varyings>&) const { return glm::vec4(1.0f); }
};
FACET_EXTERN_SHADER(BrokenShader);
