// names.cpp - the tables of names.hpp.
#include "facet/names.hpp"

#include <algorithm>

namespace facet {

std::span<const Named<Shading>> shading_names() {
  static constexpr Named<Shading> kNames[] = {{"automatic", Shading::automatic}, {"unlit", Shading::unlit},
                                              {"flat", Shading::flat},           {"gouraud", Shading::gouraud},
                                              {"phong", Shading::phong},         {"blinn-phong", Shading::blinn_phong},
                                              {"normals", Shading::normals},     {"depth", Shading::depth}};
  return kNames;
}

std::span<const Named<CullMode>> cull_mode_names() {
  static constexpr Named<CullMode> kNames[] = {
      {"back", CullMode::back}, {"front", CullMode::front}, {"none", CullMode::none}};
  return kNames;
}

std::span<const Named<ToneMapping>> tone_mapping_names() {
  static constexpr Named<ToneMapping> kNames[] = {
      {"neutral", ToneMapping::neutral}, {"aces", ToneMapping::aces}, {"none", ToneMapping::none}};
  return kNames;
}

std::span<const Named<PointShape>> point_shape_names() {
  static constexpr Named<PointShape> kNames[] = {{"square", PointShape::square}, {"disc", PointShape::disc}};
  return kNames;
}

std::span<const Named<ColorMap>> color_map_names() {
  static constexpr Named<ColorMap> kNames[] = {
      {"none", ColorMap::none}, {"height", ColorMap::height}, {"intensity", ColorMap::intensity}};
  return kNames;
}

std::span<const Named<Projection>> projection_names() {
  static constexpr Named<Projection> kNames[] = {{"perspective", Projection::perspective},
                                                 {"orthographic", Projection::orthographic},
                                                 {"frustum", Projection::frustum},
                                                 {"oblique", Projection::oblique},
                                                 {"isometric", Projection::isometric},
                                                 {"dimetric", Projection::dimetric},
                                                 {"trimetric", Projection::trimetric},
                                                 {"front", Projection::front},
                                                 {"top", Projection::top},
                                                 {"side", Projection::side}};
  return kNames;
}

std::span<const Named<bool BufferRequest::*>> buffer_names() {
  static constexpr Named<bool BufferRequest::*> kNames[] = {{"color", &BufferRequest::color},
                                                            {"depth", &BufferRequest::depth},
                                                            {"normal", &BufferRequest::normal},
                                                            {"ids", &BufferRequest::ids},
                                                            {"mask", &BufferRequest::mask},
                                                            {"motion", &BufferRequest::motion}};
  return kNames;
}

std::optional<Shading> parse_shading(std::string_view name) {
  std::string spelled(name);
  std::replace(spelled.begin(), spelled.end(), '_', '-');
  return parse_name(shading_names(), spelled);
}

std::optional<Projection> parse_projection(std::string_view name) { return parse_name(projection_names(), name); }

}  // namespace facet
