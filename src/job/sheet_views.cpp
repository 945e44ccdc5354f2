// sheet_views.cpp - the contact sheet's standard views: their names, labels and cameras.
#include "facet/sheet_views.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace facet {

namespace {

struct Named {
  const char* name;
  SheetView view;
};
constexpr Named kNames[] = {{"front", SheetView::front},
                            {"top", SheetView::top},
                            {"side", SheetView::side},
                            {"iso", SheetView::isometric},
                            {"isometric", SheetView::isometric},
                            {"dimetric", SheetView::dimetric},
                            {"trimetric", SheetView::trimetric},
                            {"oblique", SheetView::oblique},
                            {"one-point", SheetView::one_point},
                            {"two-point", SheetView::two_point},
                            {"three-point", SheetView::three_point},
                            {"perspective", SheetView::three_point}};

}  // namespace

std::optional<SheetView> parse_sheet_view(std::string_view name) {
  for (const Named& n : kNames)
    if (name == n.name) return n.view;
  return std::nullopt;
}

std::vector<SheetView> parse_sheet_views(std::string_view list) {
  std::vector<SheetView> views;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    const std::optional<SheetView> view = parse_sheet_view(name);
    if (!view)
      throw std::invalid_argument(
          "views: unknown view '" + std::string(name) +
          "' (front, top, side, iso, dimetric, trimetric, oblique, one-point, two-point, three-point)");
    views.push_back(*view);
    start = comma + 1;
  }
  return views;
}

const char* sheet_view_label(SheetView view) {
  switch (view) {
    case SheetView::front: return "front";
    case SheetView::top: return "top";
    case SheetView::side: return "side";
    case SheetView::isometric: return "isometric";
    case SheetView::dimetric: return "dimetric";
    case SheetView::trimetric: return "trimetric";
    case SheetView::oblique: return "oblique (cabinet)";
    case SheetView::one_point: return "one-point perspective";
    case SheetView::two_point: return "two-point perspective";
    case SheetView::three_point: return "three-point perspective";
  }
  return "";
}

CameraSpec sheet_camera(SheetView view, const CameraSpec& base, const Framing& framing, float aspect) {
  CameraSpec camera;
  camera.up = base.up;
  camera.view_angle_degrees = base.view_angle_degrees;
  // A level eye at `degrees` round from the front, framing the model's sphere with `facet render`'s 8% margin.
  const auto level = [&](float degrees) {
    const float half_vertical = glm::radians(camera.view_angle_degrees) * 0.5f;
    const float half_horizontal = std::atan(std::tan(half_vertical) * aspect);
    const float distance = 1.08f * std::max(framing.radius, 1e-6f) / std::sin(std::min(half_vertical, half_horizontal));
    const glm::mat3 world_from_upright = glm::transpose(upright_from_model(camera.up));
    const float a = glm::radians(degrees);
    camera.position = framing.center + world_from_upright * glm::vec3(std::sin(a), 0.0f, std::cos(a)) * distance;
    camera.focal_point = framing.center;
  };
  switch (view) {
    case SheetView::front: camera.projection = Projection::front; break;
    case SheetView::top: camera.projection = Projection::top; break;
    case SheetView::side: camera.projection = Projection::side; break;
    case SheetView::isometric: camera.projection = Projection::isometric; break;
    case SheetView::dimetric: camera.projection = Projection::dimetric; break;
    case SheetView::trimetric: camera.projection = Projection::trimetric; break;
    case SheetView::oblique: camera.projection = Projection::oblique; break;
    case SheetView::one_point: level(0.0f); break;
    case SheetView::two_point: level(45.0f); break;
    case SheetView::three_point: break;
  }
  return camera;
}

}  // namespace facet
