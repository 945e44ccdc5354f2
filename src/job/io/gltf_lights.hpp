// gltf_lights.hpp - a node's KHR_lights_punctual light as facet's Light, checked and placed in the world.
#pragma once

#include <tiny_gltf.h>

#include <optional>
#include <set>
#include <string>

#include <glm/glm.hpp>

#include "facet/light.hpp"

namespace facet {

// The light node `n` places (KHR_lights_punctual's "light" in its extensions), positioned and aimed by `world` (a
// light shines down its node's -Z), or nothing when the node places none. A light the file gets wrong (an unknown
// type, a negative or non-finite intensity or colour, a transform that is not finite) is left out with a warning,
// a bad range or cone is corrected with one; `warned` holds the lights already warned about. Throws InputError for
// a light index the file does not have.
std::optional<Light> light_of(const tinygltf::Model& model, const tinygltf::Node& n, const glm::mat4& world,
                              const std::string& source, std::set<int>& warned);

}  // namespace facet
