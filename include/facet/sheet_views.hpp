// sheet_views.hpp - the standard views of a contact sheet: the classical projections, each a camera of its own.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "facet/view_spec.hpp"

namespace facet {

// A view of the model, as drawing courses name them.
enum class SheetView {
  front,        // orthographic, looking along -Z of the model's upright frame
  top,          // orthographic, from above
  side,         // orthographic, from the right
  isometric,    // axonometric: the three axes equally foreshortened
  dimetric,     // two axes equally foreshortened
  trimetric,    // all three differently
  oblique,      // cabinet: the front face true to size, depth receding at 45 degrees, halved
  one_point,    // perspective straight at the front: one vanishing point
  two_point,    // perspective turned 45 degrees about the vertical, level: verticals stay parallel
  three_point,  // perspective from the front right, above (`facet render`'s own view)
};

// "front", "top", "side", "iso" or "isometric", "dimetric", "trimetric", "oblique", "one-point", "two-point",
// "three-point" or "perspective"; nullopt for anything else.
std::optional<SheetView> parse_sheet_view(std::string_view name);

// A comma-separated list of those names, in order; throws std::invalid_argument naming the first unknown one.
std::vector<SheetView> parse_sheet_views(std::string_view list);

// The label a sheet writes over the view: "front", "isometric", "two-point perspective", ...
const char* sheet_view_label(SheetView view);

// The camera of `view` for a model framed by `framing` in a cell of the given aspect (width / height), everything
// else (up axis, view angle) as `base` says; position, focal point, angles and windows of `base` are not used,
// since each view places its own camera. The perspective views look at the framing's centre from as far as
// `facet render` frames a model, straight from the front (one-point), from 45 degrees round and level
// (two-point), or from `facet render`'s own 3/4 view (three-point), with the model's up axis vertical.
CameraSpec sheet_camera(SheetView view, const CameraSpec& base, const Framing& framing, float aspect);

}  // namespace facet
