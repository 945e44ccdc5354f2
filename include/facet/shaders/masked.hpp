// masked.hpp - Masked<S>: a stock shader whose fragments below an alpha cutoff are discarded (glTF alphaMode MASK).
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "facet/shader.hpp"

namespace facet {

// The fragments S colours with alpha below alpha_cutoff are discarded and the rest are written opaque, so cut-out
// surfaces (leaves, fences, decals) hide what is behind them only where they are solid. Discarding means the depth
// test runs after shading, so this costs more than S alone; the Scene uses it only for masked materials.
// It holds S rather than deriving from it: a discarding shader may not have fragment_lanes (ShaderTraits), and a
// derived struct would inherit S's. So it declares exactly the hooks it has, passing needs_derivatives through.
template <class S>
struct Masked {
  using Vertex = typename S::Vertex;
  using Varyings = typename S::Varyings;
  static constexpr bool may_discard = true;
  static constexpr bool needs_derivatives = ShaderTraits<S>::needs_derivatives;
  S shader;
  float alpha_cutoff = 0.5f;
  // When set, a kept fragment writes its triangle's entry (indexed by Fragment::primitive) instead of S's colour:
  // the id pass's keys, cut by the same alpha.
  const glm::vec4* replace = nullptr;

  VertexOut<Varyings> vertex(const Vertex& v) const { return shader.vertex(v); }
  std::optional<glm::vec4> fragment(const Fragment<Varyings>& f) const {
    const glm::vec4 color = shader.fragment(f);
    if (!(color.a >= alpha_cutoff)) return std::nullopt;
    return replace ? replace[f.primitive] : glm::vec4(glm::vec3(color), 1.0f);
  }
};

}  // namespace facet
