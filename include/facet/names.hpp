// names.hpp - the names of the library's choices, spelled once for every face (the CLI, Python, the viewer).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "facet/render_job.hpp"
#include "facet/render_state.hpp"
#include "facet/scene.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/view_spec.hpp"

namespace facet {

// A choice and its name, as `facet render` spells it (--shading blinn-phong) and the other faces accept it.
template <class T>
struct Named {
  const char* name;
  T value;
};

// "automatic" (the model's own look), "unlit", "flat", "gouraud", "phong", "blinn-phong", "normals", "depth".
std::span<const Named<Shading>> shading_names();
// "back", "front", "none".
std::span<const Named<CullMode>> cull_mode_names();
// "neutral" (Khronos PBR Neutral), "aces", "none".
std::span<const Named<ToneMapping>> tone_mapping_names();
// "perspective", "orthographic", "frustum", "oblique", "isometric", "dimetric", "trimetric", "front", "top", "side".
std::span<const Named<Projection>> projection_names();
// The buffers a render can return: "color", "depth", "normal", "ids", "mask", each a field of BufferRequest.
std::span<const Named<bool BufferRequest::*>> buffer_names();

// The value named `name`; nullopt for anything else.
template <class T>
std::optional<T> parse_name(std::span<const Named<T>> names, std::string_view name) {
  for (const Named<T>& n : names)
    if (name == n.name) return n.value;
  return std::nullopt;
}
// The name of `value` (every value has one).
template <class T>
const char* name_of(std::span<const Named<T>> names, T value) {
  for (const Named<T>& n : names)
    if (n.value == value) return n.name;
  return "";
}
// The names joined by ", ", for messages that say what is accepted.
template <class T>
std::string listed(std::span<const Named<T>> names) {
  std::string out;
  for (const Named<T>& n : names) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

// A shading by its name, or by the spelling with underscores ("blinn_phong") that Python used first.
std::optional<Shading> parse_shading(std::string_view name);
// A projection by its name.
std::optional<Projection> parse_projection(std::string_view name);

}  // namespace facet
