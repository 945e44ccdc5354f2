// look.cpp - a LookSpec applied: the scene's drawing options and lights, the mesh's colour, the clear colour.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "facet/render_job.hpp"
#include "facet/warnings.hpp"

namespace facet {

namespace {
constexpr float kPi = 3.14159265358979f;
}  // namespace

SceneOptions scene_options(const LookSpec& look, const glm::mat4& view_from_world, Shading default_shading,
                           glm::vec3 background, std::span<const Light> model_lights, UpAxis up) {
  SceneOptions options;
  options.shading = look.shading.value_or(default_shading);
  glm::vec3 light;
  if (look.light_direction) {
    if (*look.light_direction == glm::vec3(0.0f)) throw std::invalid_argument("light direction: must not be zero");
    light = *look.light_direction;
  } else {
    light = glm::transpose(glm::mat3(view_from_world)) * kHeadlightFromCamera;  // fixed to the camera
  }
  if (look.ambient) {
    const glm::vec3 a = *look.ambient;
    if (!(a.r >= 0.0f && a.g >= 0.0f && a.b >= 0.0f) || !std::isfinite(a.r + a.g + a.b))
      throw std::invalid_argument("ambient light: must be finite and not negative");
    options.ambient = a;
  }
  if (options.shading == Shading::automatic) {
    if (!(look.exposure > 0.0f) || !std::isfinite(look.exposure))
      throw std::invalid_argument("exposure: must be a finite number above 0");
    if (!look.ambient) options.environment = environment_for(look, up);
    options.tone_mapping = look.tone_mapping;
    options.exposure = look.exposure;
    if (!(look.hdri_blur >= 0.0f && look.hdri_blur <= 1.0f))
      throw std::invalid_argument("environment blur: must lie between 0 and 1");
    options.environment_background = look.hdri_background;
    options.background_blur = look.hdri_blur;
    options.lights.clear();
    if (look.model_lights) options.lights.assign(model_lights.begin(), model_lights.end());
    options.lights.insert(options.lights.end(), look.lights.begin(), look.lights.end());
    if (look.light_direction) options.lights.push_back(Light{Light::Kind::directional, light, glm::vec3(1.0f), kPi});
    options.shadows = look.shadows;
    options.ambient_occlusion = look.ambient_occlusion;
    if (look.shadows && std::none_of(options.lights.begin(), options.lights.end(),
                                     [](const Light& l) { return l.kind != Light::Kind::point && l.casts_shadows; }))
      warn(
          "shadows: no directional or spot light to cast them (the environment casts none); give a light "
          "direction");
  } else {
    if (look.ambient || !look.lights.empty()) options.lights = look.lights;
    else options.lights = {Light{Light::Kind::directional, light, glm::vec3(1.0f), 1.0f}};
  }
  if (look.color) options.color = glm::vec4(*look.color, 1.0f);
  options.cull = look.cull.value_or(CullMode::none);
  options.cull_single_sided = !look.cull;
  options.depth_test = look.depth_test;
  options.painter = look.painter;
  options.wireframe = look.wireframe;
  options.edges = look.edges;
  if (look.world_point_size ? !(look.point_size > 0.0f && std::isfinite(look.point_size))
                            : !(look.point_size > 0.0f && look.point_size <= kMaxPointSize))
    throw std::invalid_argument(look.world_point_size
                                    ? "point size: must be a finite size above 0"
                                    : "point size: must be above 0 and at most " +
                                          std::to_string(static_cast<int>(kMaxPointSize)) + " pixels");
  options.point_size = look.point_size;
  options.world_point_size = look.world_point_size;
  if (look.eye_dome_lighting) options.eye_dome_lighting = *look.eye_dome_lighting;  // checked by Scene::render
  options.point_shape = look.point_shape;
  // Wireframe lines take the colour asked for, else white; on a light background white lines would vanish.
  const float luminance = glm::dot(background, glm::vec3(0.2126f, 0.7152f, 0.0722f));
  if (look.wireframe && !options.color && luminance > 0.5f) options.color = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);
  return options;
}

std::shared_ptr<const Environment> environment_for(const LookSpec& look, UpAxis up) {
  if (!std::isfinite(look.hdri_rotation)) throw std::invalid_argument("environment rotation: must be finite");
  if (look.hdri.empty() && look.hdri_rotation == 0.0f && up == UpAxis::pos_y) return studio_lighting();
  // A few environments at most in a process; each is a few MB once prefiltered.
  static std::mutex mutex;
  static std::map<std::tuple<std::string, float, UpAxis>, std::shared_ptr<const Environment>> cache;
  const std::tuple<std::string, float, UpAxis> key{look.hdri.string(), look.hdri_rotation, up};
  const std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<const Environment>& found = cache[key];
  if (!found) {
    const EnvironmentImage image = look.hdri.empty() ? studio_environment() : read_environment_image(look.hdri);
    // The environment's up (+Y) turned to the model's up axis, as the camera's view up is.
    found =
        std::make_shared<const Environment>(image, look.hdri_rotation, 1.0f, glm::transpose(upright_from_model(up)));
  }
  return found;
}

void apply_look_color(Mesh& mesh, const LookSpec& look) {
  if (!look.color) return;
  mesh.colors.clear();
  mesh.face_colors.clear();
}

void apply_color_map(Mesh& mesh, const LookSpec& look, UpAxis up) {
  if (look.color_map == ColorMap::none) return;
  if (look.color) throw std::invalid_argument("colour map: cannot be combined with a colour for the whole model");
  if (look.color_map == ColorMap::intensity) {
    if (mesh.intensities.size() != mesh.positions.size() || mesh.positions.empty())
      throw std::invalid_argument(
          "colour map intensity: the model has no intensities (a PLY or PCD intensity property, a .pts file, or "
          "x y z intensity text)");
    float weakest = std::numeric_limits<float>::infinity(), strongest = -weakest;
    for (const float i : mesh.intensities)
      if (std::isfinite(i)) weakest = std::min(weakest, i), strongest = std::max(strongest, i);
    mesh.face_colors.clear();
    mesh.colors.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const float i = mesh.intensities[v];
      const float t = strongest > weakest && std::isfinite(i) ? (i - weakest) / (strongest - weakest) : 0.0f;
      mesh.colors[v] = glm::vec4(glm::vec3(t), 1.0f);
    }
    return;
  }
  // Display values (Mesh::colors), evenly spaced from the lowest height to the highest.
  constexpr glm::vec3 kStops[] = {
      {0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 1.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  constexpr int kLast = static_cast<int>(std::size(kStops)) - 1;
  const glm::vec3 axis = glm::transpose(upright_from_model(up))[1];  // the model's up, in its own coordinates
  float low = std::numeric_limits<float>::infinity(), high = -low;
  for (const glm::vec3& p : mesh.positions) {
    const float h = glm::dot(p, axis);
    if (!std::isfinite(h)) continue;
    low = std::min(low, h);
    high = std::max(high, h);
  }
  mesh.face_colors.clear();
  mesh.colors.resize(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const float h = glm::dot(mesh.positions[v], axis);
    const float t = high > low && std::isfinite(h) ? (h - low) / (high - low) * kLast : 0.0f;
    const int stop = std::clamp(static_cast<int>(t), 0, kLast - 1);
    mesh.colors[v] = glm::vec4(glm::mix(kStops[stop], kStops[stop + 1], std::clamp(t - stop, 0.0f, 1.0f)), 1.0f);
  }
}

float eye_dome_lighting_for(const LookSpec& look, const Mesh& as_loaded) {
  if (look.eye_dome_lighting) return *look.eye_dome_lighting;
  const bool bare_cloud = as_loaded.indices.empty() && !as_loaded.points.empty() && !as_loaded.splats &&
                          as_loaded.normals.size() != as_loaded.positions.size() &&
                          as_loaded.colors.size() != as_loaded.positions.size();
  return bare_cloud ? kDefaultEyeDomeLighting : 0.0f;
}

glm::vec4 clear_color(const LookSpec& look, glm::vec3 fallback) {
  return {look.background.value_or(fallback), look.transparent_background ? 0.0f : 1.0f};
}

}  // namespace facet
