// fragment_lanes_non_const.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: a fragment_lanes that is not const, so the pipeline could not call it.
// expect-error: facet shader rule: fragment_lanes() is a const member function
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"

struct BrokenShader {
  struct Vertex {
    glm::vec3 position;
  };
  struct Varyings {
    glm::vec4 color;
  };
  static constexpr bool may_discard = false;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  glm::vec4 fragment(const facet::Fragment<Varyings>&) const { return glm::vec4(1.0f); }
  facet::simd::Color fragment_lanes(const facet::FragmentLanes<Varyings>&) { return {}; }
};
FACET_EXTERN_SHADER(BrokenShader);
