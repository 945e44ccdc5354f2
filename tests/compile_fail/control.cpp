// control.cpp - a shader that keeps every rule: it must compile, so the compile_fail tests cannot pass vacuously.
#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"

struct ControlShader {
  struct Vertex {
    glm::vec3 position;
  };
  struct Varyings {  // nested structs and arrays of floats are floats too
    struct Surface {
      glm::vec3 normal;
      float roughness;
    } surface;
    std::array<float, 2> weights;
    glm::vec4 color;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;
  static constexpr bool lanes_read_primitive = false;
  glm::mat4 clip_from_object{1.0f};

  facet::VertexOut<Varyings> vertex(const Vertex& v) const {
    return {clip_from_object * glm::vec4(v.position, 1.0f), {{v.position, 0.5f}, {0.0f, 1.0f}, glm::vec4(1.0f)}};
  }
  glm::vec4 fragment(const facet::Fragment<Varyings>& f) const { return f.varyings.color + f.ddx.color; }
  facet::simd::Color fragment_lanes(const facet::FragmentLanes<Varyings>& f) const { return f.get(&Varyings::color); }
};
FACET_EXTERN_SHADER(ControlShader);

static_assert(facet::LaneShader<ControlShader> && facet::ShaderTraits<ControlShader>::needs_derivatives &&
              !facet::ShaderTraits<ControlShader>::lanes_read_primitive);
