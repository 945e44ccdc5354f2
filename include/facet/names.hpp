// names.hpp - the names of the library's choices, spelled once for every face (the CLI, Python, the viewer).
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include "facet/named.hpp"
#include "facet/render_job.hpp"
#include "facet/render_state.hpp"
#include "facet/scene.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/view_spec.hpp"

namespace facet {

// "automatic" (the model's own look), "unlit", "flat", "gouraud", "phong", "blinn-phong", "normals", "depth".
std::span<const Named<Shading>> shading_names();
// "back", "front", "none".
std::span<const Named<CullMode>> cull_mode_names();
// "neutral" (Khronos PBR Neutral), "aces", "none".
std::span<const Named<ToneMapping>> tone_mapping_names();
// "square", "disc".
std::span<const Named<PointShape>> point_shape_names();
// "none", "height".
std::span<const Named<ColorMap>> color_map_names();
// "perspective", "orthographic", "frustum", "oblique", "isometric", "dimetric", "trimetric", "front", "top", "side".
std::span<const Named<Projection>> projection_names();
// The buffers a render can return: "color", "depth", "normal", "ids", "mask", "motion", each a field of
// BufferRequest.
std::span<const Named<bool BufferRequest::*>> buffer_names();

// A shading by its name, or by the spelling with underscores ("blinn_phong") that Python used first.
std::optional<Shading> parse_shading(std::string_view name);
// A projection by its name.
std::optional<Projection> parse_projection(std::string_view name);

}  // namespace facet
