// animation.hpp - keyframed motion as glTF keeps it: samplers of keys, channels that drive a node's properties.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace facet {

// How a sampler's value runs between two keys (glTF's animation sampler interpolation).
enum class Interpolation {
  linear,        // straight between the keys; rotations slerped along the shorter arc
  step,          // each key's value held until the next key
  cubic_spline,  // a cubic Hermite spline through the keys, with each key's in- and out-tangents
};

// The property of a node a channel drives.
enum class AnimatedProperty { translation, rotation, scale, weights };

// Keys in time and the values at them. Each key holds `width` values: 3 for a translation or scale, 4 for a rotation
// (x, y, z, w), the morph target count for weights; a cubic spline's key holds three times that: in-tangent, value,
// out-tangent, as glTF stores them.
struct AnimationSampler {
  std::vector<float> times;   // seconds, finite, strictly increasing
  std::vector<float> values;  // times.size() * width values, or three times that for a cubic spline
  std::size_t width = 0;
  Interpolation interpolation = Interpolation::linear;
};

// One animated property of one node (an index into Model::nodes), driven by a sampler of its animation.
struct AnimationChannel {
  std::uint32_t sampler = 0;
  std::uint32_t node = 0;
  AnimatedProperty property = AnimatedProperty::translation;
};

// A clip: a named set of channels that play together.
struct Animation {
  std::string name;
  std::vector<AnimationSampler> samplers;
  std::vector<AnimationChannel> channels;

  // The clip's length: its last key, over every sampler (0 for a clip of one moment).
  float duration() const;
};

// Throws InputError(source, ...) unless the sampler can be sampled: at least one key, key times finite and strictly
// increasing, `width` at least 1, as many finite values as its keys and interpolation need. `what` names the sampler
// in the message ("animation 'Walk', sampler 2").
void validate(const AnimationSampler& sampler, const std::string& what, const std::string& source);

// The sampler's value at `seconds`, into out (width values): before the first key the first key's value, after the
// last the last key's. `rotation` treats the values as quaternions (x, y, z, w): a linear step is a slerp along the
// shorter arc and a spline's result is normalised. The sampler must be valid (validate()).
void sample(const AnimationSampler& sampler, float seconds, bool rotation, std::span<float> out);

// The index of the animation a caller names: its name, or its index as a decimal number when no animation has that
// name. nullopt when neither names one.
std::optional<std::size_t> find_animation(std::span<const Animation> animations, std::string_view name);
// The same, for a model that must have it: an empty name picks the first. Throws InputError(source, ...) for a
// model without animations ("has no animation to play"), or without one of that name or index (listing those it
// has).
std::size_t animation_named(std::span<const Animation> animations, std::string_view name, const std::string& source);

}  // namespace facet
