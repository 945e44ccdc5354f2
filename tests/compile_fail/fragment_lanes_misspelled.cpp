// fragment_lanes_misspelled.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: fragment_lane for fragment_lanes, which would quietly leave the lane path unused.
// expect-error: facet shader rule: fragment_lane is not a shader hook; did you mean fragment_lanes?
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
  facet::simd::Color fragment_lane(const facet::FragmentLanes<Varyings>&) const { return {}; }
};
FACET_EXTERN_SHADER(BrokenShader);
