// fragment_lanes_may_discard.cpp - a shader that breaks one rule on purpose, so it must not compile.
// Here: fragment_lanes on a shader that may discard, which lane shading cannot do.
// expect-error: facet shader rule: fragment_lanes() needs may_discard = false
#include <cstdint>
#include <optional>
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
  static constexpr bool may_discard = true;
  facet::VertexOut<Varyings> vertex(const Vertex& v) const { return {glm::vec4(v.position, 1.0f), {}}; }
  std::optional<glm::vec4> fragment(const facet::Fragment<Varyings>&) const { return std::nullopt; }
  facet::simd::Color fragment_lanes(const facet::FragmentLanes<Varyings>&) const { return {}; }
};
FACET_EXTERN_SHADER(BrokenShader);
