// shadows.cpp - shadow maps rendered by the pipeline itself: a depth-only pass of every instance from each light.
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "facet/shaders/stock.hpp"
#include "scene/scene_impl.hpp"

namespace facet {
namespace {

using detail::PreparedMesh;
using detail::TriangleGroup;
using Prepared = std::unordered_map<const Mesh*, PreparedMesh>;

struct Sphere {
  glm::vec3 center{0.0f};
  float radius = 0.0f;
};

// A sphere around every instance's bounding sphere (the centre of their centres' box).
Sphere scene_sphere(const std::vector<Instance>& instances, const Prepared& prepared) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  std::vector<Sphere> spheres;
  for (const Instance& instance : instances) {
    const PreparedMesh& mesh = prepared.at(instance.mesh.get());
    if (mesh.vertices.empty()) continue;
    const Sphere s{glm::vec3(instance.world_from_object * glm::vec4(mesh.center, 1.0f)),
                   mesh.radius * detail::max_scale(instance.world_from_object)};
    lo = glm::min(lo, s.center);
    hi = glm::max(hi, s.center);
    spheres.push_back(s);
  }
  Sphere out;
  if (spheres.empty()) return out;
  out.center = (lo + hi) * 0.5f;
  for (const Sphere& s : spheres) out.radius = std::max(out.radius, glm::length(s.center - out.center) + s.radius);
  out.radius = std::max(out.radius, 1e-6f);
  return out;
}

// An up vector not parallel to `forward`.
glm::vec3 up_for(glm::vec3 forward) {
  return std::abs(forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

// The light's clip_from_world and the world size of one texel where the scene is.
struct LightView {
  glm::mat4 clip_from_world;
  float texel;
};

LightView directional_view(const PunctualLight& light, const Sphere& scene, int size) {
  const float r = scene.radius;
  const glm::vec3 eye = scene.center + light.vector * (2.0f * r);
  const glm::mat4 view = glm::lookAt(eye, scene.center, up_for(-light.vector));
  return {glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f) * view, 2.0f * r / static_cast<float>(size)};
}

LightView spot_view(const PunctualLight& light, const Sphere& scene, float outer_cone, int size) {
  const glm::vec3 eye = light.vector;
  const float distance = glm::length(scene.center - eye);
  const float far = distance + scene.radius;
  // Close enough to keep what lies between the light and the scene, far enough to keep depth precision.
  const float near = std::max(far * 1e-3f, distance - scene.radius);
  const float fov = std::clamp(2.0f * outer_cone, 0.01f, 3.0f);
  const glm::mat4 view = glm::lookAt(eye, eye + light.spot_direction, up_for(light.spot_direction));
  const float texel = 2.0f * std::tan(fov * 0.5f) * std::max(distance, near) / static_cast<float>(size);
  return {glm::perspective(fov, 1.0f, near, far) * view, texel};
}

}  // namespace

float Scene::Impl::bounding_radius() const { return scene_sphere(instances, prepared).radius; }

void Scene::Impl::draw_depth(Renderer& renderer, Framebuffer& target, const SceneOptions& options,
                             const glm::mat4& clip_from_world, DepthPass pass) const {
  RenderState two_sided;
  two_sided.cull = CullMode::none;  // two-sided casters: an open mesh's back faces cast too, and nothing leaks
  // Only depth is read: without colour writes the pipeline's visibility pass is the whole draw (raster_tile.hpp),
  // except for masked materials, whose discarding shader is run on every fragment.
  two_sided.color_write = false;
  for (const Instance& instance : instances) {
    const PreparedMesh& mesh = prepared.at(instance.mesh.get());
    const glm::vec4 center = instance.world_from_object * glm::vec4(mesh.center, 1.0f);
    if (mesh.vertices.empty() ||
        !sphere_in_frustum(clip_from_world, glm::vec3(center), mesh.radius * detail::max_scale(instance.world_from_object)))
      continue;
    const ObjectTransforms transforms = ObjectTransforms::make(clip_from_world, instance.world_from_object);
    const std::span<const MeshVertex> vertices(mesh.vertices);
    for (const TriangleGroup& group : mesh.groups) {
      const Material& material = detail::material_of(*instance.mesh, group);
      if (pass == DepthPass::visible && material.alpha_mode == AlphaMode::blend) continue;
      RenderState state = two_sided;
      if (pass == DepthPass::visible) {
        state = detail::surface_state(options, material, transforms.mirrored);
        state.blend = BlendMode::none;
        state.color_write = false;
        state.order = DrawOrder::as_given;
        state.depth_func = DepthFunc::less;  // the nearest surface, whatever order the frame draws in
      }
      if (detail::is_masked(options, material)) {
        Masked<UnlitShader> cut{
            UnlitShader{transforms.clip_from_object, detail::surface_color(options, material, mesh, group)}};
        cut.alpha_cutoff = material.alpha_cutoff;
        renderer.draw(target, cut, vertices, group.indices, state);
      } else {
        renderer.draw(target, DepthShader{transforms.clip_from_object, glm::mat4(1.0f), 0.0f, 1.0f}, vertices,
                      group.indices, state);
      }
    }
  }
}

void Scene::Impl::shadow_lights(Renderer& renderer, const SceneOptions& options, std::vector<PunctualLight>& lights,
                                int size) {
  const Sphere sphere = scene_sphere(instances, prepared);
  if (sphere.radius <= 0.0f) return;
  // What the maps depend on: each casting light's view, the instances, and the colour override (masked cutoffs).
  ShadowCache::Key key{size, {}, {}, options.color};
  std::vector<LightView> views;
  for (const PunctualLight& light : lights) {
    if (!light.casts_shadows) continue;
    views.push_back(light.directional ? directional_view(light, sphere, size)
                                      : spot_view(light, sphere, light.outer_cone, size));
    key.views.push_back(views.back().clip_from_world);
  }
  if (views.empty()) return;
  for (const Instance& instance : instances) key.casters.emplace_back(instance.mesh.get(), instance.world_from_object);
  // A turntable, a viewer or a batch of views moves the camera, not the lights: the maps of the last frame stand.
  if (!(shadows.key == key)) {
    shadows.maps.clear();
    shadows.maps.reserve(views.size());
    if (!shadows.target || shadows.target->width() != size) shadows.target = std::make_unique<Framebuffer>(size, size, 1);
    for (const LightView& view : views) {
      renderer.clear(*shadows.target, glm::vec4(0.0f), 1.0f);
      draw_depth(renderer, *shadows.target, options, view.clip_from_world, DepthPass::casters);
      renderer.finish(*shadows.target);
      shadows.maps.emplace_back(view.clip_from_world, size, shadows.target->depth(), 1.5f * view.texel);
    }
    shadows.key = std::move(key);
  }
  std::size_t next = 0;
  for (PunctualLight& light : lights)
    if (light.casts_shadows) light.shadow = &shadows.maps[next++];
}

}  // namespace facet
