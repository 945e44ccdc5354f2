// gltf_lights.cpp - KHR_lights_punctual read: each light a node places, with the extension's defaults and limits.
#include "job/io/gltf_lights.hpp"

#include <algorithm>
#include <cmath>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"

namespace facet {
namespace {

constexpr float kHalfPi = 1.57079632679f;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The light index the node's extension names, or -1.
int light_index(const tinygltf::Node& n, const std::string& source) {
  const auto it = n.extensions.find("KHR_lights_punctual");
  if (it == n.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return -1;
  const tinygltf::Value& index = it->second.Get("light");
  if (!index.IsNumber() && !index.IsInt())
    throw InputError(source, "a node's KHR_lights_punctual light is not an index");
  const double value = index.GetNumberAsDouble();
  if (!(value >= 0.0 && value < 1e9) || value != std::floor(value))
    throw InputError(source, "a node's KHR_lights_punctual light is not an index");
  return static_cast<int>(value);
}

}  // namespace

std::optional<Light> light_of(const tinygltf::Model& model, const tinygltf::Node& n, const glm::mat4& world,
                              const std::string& source, std::set<int>& warned) {
  const int index = light_index(n, source);
  if (index < 0) return std::nullopt;
  if (static_cast<std::size_t>(index) >= model.lights.size())
    throw InputError(source, "light " + std::to_string(index) + " does not exist");
  const tinygltf::Light& l = model.lights[static_cast<std::size_t>(index)];
  const std::string name = "light " + std::to_string(index);
  const auto problem = [&](const std::string& what) {
    if (warned.insert(index).second) warn(source, name + " " + what);
  };

  Light out;
  out.name = l.name;
  if (l.type == "directional") {
    out.kind = Light::Kind::directional;
  } else if (l.type == "point") {
    out.kind = Light::Kind::point;
  } else if (l.type == "spot") {
    out.kind = Light::Kind::spot;
  } else {
    problem("has an unknown type; it is left out");
    return std::nullopt;
  }
  if (!l.color.empty()) {
    if (l.color.size() != 3) {
      problem("has a colour that is not RGB; it is left out");
      return std::nullopt;
    }
    out.color =
        glm::vec3(static_cast<float>(l.color[0]), static_cast<float>(l.color[1]), static_cast<float>(l.color[2]));
  }
  out.intensity = static_cast<float>(l.intensity);
  if (!finite(out.color) || glm::min(out.color, glm::vec3(0.0f)) != glm::vec3(0.0f) || !std::isfinite(out.intensity) ||
      out.intensity < 0.0f) {
    problem("has a negative or non-finite colour or intensity; it is left out");
    return std::nullopt;
  }
  out.range = static_cast<float>(l.range);
  if (!(out.range >= 0.0f) || !std::isfinite(out.range)) {
    problem("has a range that is not a positive number; its light is not cut off");
    out.range = 0.0f;
  }
  if (out.kind == Light::Kind::spot) {
    float inner = static_cast<float>(l.spot.innerConeAngle), outer = static_cast<float>(l.spot.outerConeAngle);
    if (!(inner >= 0.0f && inner < outer && outer <= kHalfPi)) {
      problem("has cone angles outside 0 <= inner < outer <= pi/2; they are clamped");
      outer = std::isfinite(outer) ? std::clamp(outer, 1e-3f, kHalfPi) : kHalfPi / 2.0f;
      inner = std::isfinite(inner) ? std::clamp(inner, 0.0f, outer * 0.999f) : 0.0f;
    }
    out.inner_cone = inner;
    out.outer_cone = outer;
  }
  if (!place_light(out, world)) {
    problem("is placed by a transform that is not finite or flattens its direction; it is left out");
    return std::nullopt;
  }
  return out;
}

}  // namespace facet
