// masked.hpp - Masked<S>: a stock shader whose fragments below an alpha cutoff are discarded (glTF alphaMode MASK).
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "facet/shader.hpp"

namespace facet {

// The fragments S colours with alpha below alpha_cutoff are discarded and the rest are written opaque, so cut-out
// surfaces (leaves, fences, decals) hide what is behind them only where they are solid. Discarding means the depth
// test runs after shading, so this costs more than S alone; the Scene uses it only for masked materials.
template <class S>
struct Masked : S {
  static constexpr bool may_discard = true;
  float alpha_cutoff = 0.5f;
  // When set, a kept fragment writes its triangle's entry (indexed by Fragment::primitive) instead of S's colour:
  // the id pass's keys, cut by the same alpha.
  const glm::vec4* replace = nullptr;

  std::optional<glm::vec4> fragment(const Fragment<typename S::Varyings>& f) const {
    const glm::vec4 color = S::fragment(f);
    if (!(color.a >= alpha_cutoff)) return std::nullopt;
    return replace ? replace[f.primitive] : glm::vec4(glm::vec3(color), 1.0f);
  }
};

}  // namespace facet
