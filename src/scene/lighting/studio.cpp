// studio.cpp - facet's built-in studio environment: a soft dome, a floor and three softboxes, made procedurally.
#include <algorithm>
#include <cmath>
#include <memory>

#include "facet/environment.hpp"
#include "facet/shaders/brdf.hpp"
#include "scene/lighting/sampling.hpp"

namespace facet {

namespace {

// A round softbox: full radiance inside `radius` (radians) of its centre, fading to nothing over `edge` beyond
// (smoothly, by the cosine of the angle, which needs no inverse trigonometry per texel).
struct Softbox {
  glm::vec3 towards;  // unit direction from the model to the light
  float cos_inner, cos_outer;
  glm::vec3 radiance;
  Softbox(glm::vec3 direction, float radius, float edge, glm::vec3 light)
      : towards(glm::normalize(direction)),
        cos_inner(std::cos(radius)),
        cos_outer(std::cos(radius + edge)),
        radiance(light) {}
  glm::vec3 at(glm::vec3 d) const {
    const float t = std::clamp((cos_inner - glm::dot(d, towards)) / (cos_inner - cos_outer), 0.0f, 1.0f);
    return radiance * (1.0f - t * t * (3.0f - 2.0f * t));
  }
};

}  // namespace

EnvironmentImage studio_environment() {
  // Above the horizon a grey dome, brightest overhead; below it a darker floor. Key light above and to the front
  // left (front: +Z), a weaker fill to the right, a rim light behind; all neutral white, so that the look changes
  // no colour.
  const Softbox lights[] = {
      {glm::vec3(-0.6f, 0.8f, 0.7f), 0.22f, 0.12f, glm::vec3(4.0f)},
      {glm::vec3(0.9f, 0.25f, 0.3f), 0.30f, 0.15f, glm::vec3(1.2f)},
      {glm::vec3(0.2f, 0.6f, -0.9f), 0.18f, 0.10f, glm::vec3(2.5f)},
  };
  EnvironmentImage image;
  image.width = 256;
  image.height = 128;
  image.texels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  const ColumnAzimuths phi = column_azimuths(image.width);
  for (int y = 0; y < image.height; ++y) {
    const float theta = (static_cast<float>(y) + 0.5f) / static_cast<float>(image.height) * brdf::kPi;
    const float cos_theta = std::cos(theta), sin_theta = std::sin(theta);
    for (int x = 0; x < image.width; ++x) {
      const std::size_t column = static_cast<std::size_t>(x);
      const glm::vec3 d(phi.cos[column] * sin_theta, cos_theta, phi.sin[column] * sin_theta);
      // The dome from 0.3 at the horizon to 0.5 overhead; the floor 0.12, blended over a few degrees.
      const float dome = 0.3f + 0.2f * std::max(d.y, 0.0f);
      const float floor_blend = std::clamp(d.y * 10.0f + 0.5f, 0.0f, 1.0f);
      glm::vec3 radiance(0.12f + (dome - 0.12f) * floor_blend);
      for (const Softbox& light : lights) radiance += light.at(d);
      image.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)] =
          radiance;
    }
  }
  return image;
}

std::shared_ptr<const Environment> studio_lighting() {
  static const std::shared_ptr<const Environment> studio = std::make_shared<const Environment>(studio_environment());
  return studio;
}

}  // namespace facet
