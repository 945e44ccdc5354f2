// color.hpp - sRGB's transfer functions for colours given as numbers (material factors, vertex colours).
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace facet {

// IEC 61966-2-1, exactly (std::pow), for values in [0, 1]; outside it they are clamped. Alpha is never encoded.
inline float srgb_to_linear(float c) {
  c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
inline float linear_to_srgb(float x) {
  x = x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}
inline glm::vec3 srgb_to_linear(glm::vec3 c) { return {srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)}; }
inline glm::vec3 linear_to_srgb(glm::vec3 c) { return {linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b)}; }
inline glm::vec4 srgb_to_linear(glm::vec4 c) { return {srgb_to_linear(glm::vec3(c)), c.a}; }
inline glm::vec4 linear_to_srgb(glm::vec4 c) { return {linear_to_srgb(glm::vec3(c)), c.a}; }

}  // namespace facet
