// light.hpp - a light as a scene or a model file places it: directional, point or spot (glTF's KHR_lights_punctual).
#pragma once

#include <string>

#include <glm/glm.hpp>

namespace facet {

// Colour and intensity are in linear light. Under the physically based look a directional light's colour times
// intensity is the irradiance it gives a surface facing it (lux, as glTF has it), and a point or spot light's is
// its intensity (candela): its irradiance at distance d is that over d^2. The classic shadings (Shading::flat ...
// blinn_phong) use colour times intensity as is, point lights unattenuated, and take no spot lights.
struct Light {
  enum class Kind { directional, point, spot } kind = Kind::directional;
  glm::vec3 vector{0.4f, 0.7f, 0.6f};  // directional: direction towards the light; point, spot: world position
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  glm::vec3 spot_direction{0.0f, 0.0f, -1.0f};  // spot: the way it shines, world space
  float range = 0.0f;                           // point, spot: where its light fades to nothing; 0 = unlimited
  float inner_cone = 0.0f;                      // spot: half-angles in radians, 0 <= inner < outer <= pi/2; full
  float outer_cone = 0.7853982f;                //   light inside inner, none outside outer
  bool casts_shadows = true;  // directional and spot: when the options draw shadows
  std::string name{};
};

}  // namespace facet
