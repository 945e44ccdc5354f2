// scene.cpp - the Scene: mesh preparation cache, frustum rejection, painter's instance order; plus linear depth.
#include "facet/scene.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "facet/splats.hpp"
#include "scene/eye_dome_lighting.hpp"
#include "scene/scene_impl.hpp"

namespace facet {

Scene::Scene() : impl_(std::make_unique<Impl>()) {}
Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

void Scene::add(Instance instance) {
  if (!instance.mesh) throw std::invalid_argument("Scene::add: instance without a mesh");
  const Mesh* mesh = instance.mesh.get();
  if (!impl_->prepared.contains(mesh)) impl_->prepared.emplace(mesh, detail::prepare_mesh(*mesh, impl_->textures));
  impl_->instances.push_back(std::move(instance));
  impl_->shadows.key = {};  // a new mesh may sit where a removed one was: the cache's pointers no longer tell
}

void Scene::set_transform(std::size_t index, const glm::mat4& world_from_object) {
  impl_->instances.at(index).world_from_object = world_from_object;
}

void Scene::remove(std::size_t index) {
  std::vector<Instance>& instances = impl_->instances;
  const std::shared_ptr<const Mesh> mesh = instances.at(index).mesh;
  instances.erase(instances.begin() + static_cast<std::ptrdiff_t>(index));
  // The address keys the prepared data only while an instance holds the mesh alive (see Impl::prepared).
  if (std::none_of(instances.begin(), instances.end(), [&](const Instance& i) { return i.mesh == mesh; }))
    impl_->prepared.erase(mesh.get());
  impl_->shadows.key = {};
}

std::size_t Scene::size() const { return impl_->instances.size(); }

const std::vector<Instance>& Scene::instances() const { return impl_->instances; }

LightBlock make_light_block(const SceneOptions& options) {
  LightBlock block;
  block.ambient = options.ambient;
  for (const Light& light : options.lights) {
    if (block.count >= kMaxLights) break;
    const glm::vec3 color = light.color * light.intensity;
    if (light.kind == Light::Kind::directional) {
      // A zero direction would normalize to NaN and blacken every pixel; such a light is skipped instead.
      if (glm::dot(light.vector, light.vector) > 0.0f) block.add_directional(light.vector, color);
    } else if (light.kind == Light::Kind::point) {
      block.add_point(light.vector, color);
    }
  }
  return block;
}

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every light of the options the physically based look can use; a light with a zero or non-finite vector, or
// whose colour is not finite and non-negative, would turn pixels NaN and is left out.
std::vector<PunctualLight> punctual_lights(const SceneOptions& options) {
  std::vector<PunctualLight> out;
  for (const Light& light : options.lights) {
    const glm::vec3 color = light.color * light.intensity;
    if (!finite(color) || glm::min(color, glm::vec3(0.0f)) != glm::vec3(0.0f) || !finite(light.vector)) continue;
    if (light.kind == Light::Kind::directional && glm::dot(light.vector, light.vector) == 0.0f) continue;
    if (light.kind == Light::Kind::spot &&
        (!finite(light.spot_direction) || glm::dot(light.spot_direction, light.spot_direction) == 0.0f ||
         !std::isfinite(light.inner_cone) || !std::isfinite(light.outer_cone)))
      continue;
    if (!(light.range >= 0.0f) || !std::isfinite(light.range)) continue;
    out.push_back(PunctualLight::from(light));
  }
  return out;
}

}  // namespace

detail::FrameContext detail::frame_context(const View& view, const SceneOptions& options) {
  return {&view,
          &options,
          view.clip_from_view * view.view_from_world,
          glm::vec3(glm::inverse(view.view_from_world)[3]),
          make_light_block(options),
          punctual_lights(options)};
}

float Scene::Impl::view_z(const detail::FrameContext& frame, std::size_t instance) const {
  const glm::vec4 center =
      instances[instance].world_from_object * glm::vec4(prepared_of(instances[instance]).center, 1);
  return (frame.view->view_from_world * center).z;
}

namespace {

// Farthest first; ties keep the order of addition. std::sort with that tie-break needs no temporary buffer, unlike
// stable_sort.
void sort_back_to_front(std::vector<std::pair<float, std::size_t>>& by_depth) {
  std::sort(by_depth.begin(), by_depth.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second < b.second);
  });
}

}  // namespace

std::vector<std::size_t> Scene::Impl::visible(const detail::FrameContext& frame) const {
  std::vector<std::pair<float, std::size_t>> found;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const detail::PreparedMesh& mesh = prepared_of(instances[i]);
    if (mesh.vertices.empty() || (mesh.groups.empty() && mesh.points.indices.empty())) continue;
    const glm::vec4 center = instances[i].world_from_object * glm::vec4(mesh.center, 1.0f);
    const float radius = mesh.radius * detail::max_scale(instances[i].world_from_object);
    if (!sphere_in_frustum(frame.clip_from_world, glm::vec3(center), radius)) continue;
    found.emplace_back(view_z(frame, i), i);
  }
  // The painter's algorithm sorts triangles within a draw; sorting the instances too extends it across draws.
  if (frame.options->painter) sort_back_to_front(found);
  std::vector<std::size_t> order(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) order[k] = found[k].second;
  return order;
}

std::vector<std::size_t> Scene::Impl::blended(const detail::FrameContext& frame,
                                              const std::vector<std::size_t>& visible) const {
  std::vector<std::pair<float, std::size_t>> found;
  for (const std::size_t i : visible) {
    const detail::PreparedMesh& mesh = prepared_of(instances[i]);
    if (std::any_of(mesh.groups.begin(), mesh.groups.end(),
                    [&](const detail::TriangleGroup& g) { return detail::is_blended(*instances[i].mesh, g); }))
      found.emplace_back(view_z(frame, i), i);
  }
  sort_back_to_front(found);
  std::vector<std::size_t> order(found.size());
  for (std::size_t k = 0; k < found.size(); ++k) order[k] = found[k].second;
  return order;
}

std::size_t Scene::render(Renderer& renderer, Framebuffer& target, const View& view, const SceneOptions& options) {
  detail::FrameContext frame = detail::frame_context(view, options);
  if (options.shadows && options.shading == Shading::automatic) {
    if (options.shadow_map_size < 1 || options.shadow_map_size > 8192)
      throw std::invalid_argument("shadow map size: must lie in 1..8192");
    impl_->shadow_lights(renderer, options, frame.punctual, options.shadow_map_size);
  }
  if (options.ambient_occlusion && options.shading == Shading::automatic) {
    impl_->ambient_occlusion(renderer, options, view, target.width(), target.height(),
                             kOcclusionRadius * impl_->bounding_radius());
    frame.occlusion = impl_->occlusion.open.data();
    frame.occlusion_x = impl_->occlusion.window.x0;
    frame.occlusion_y = impl_->occlusion.window.y0;
    frame.occlusion_width = impl_->occlusion.z.width;
    frame.occlusion_height = impl_->occlusion.z.height;
  }
  if (options.environment_background && options.environment && options.shading == Shading::automatic)
    detail::draw_environment_background(renderer, target, frame);
  // Splats composite over the surfaces by depth: the target keeps its depth for them when the scene has both.
  bool splats = false, surfaces = false;
  for (const Instance& instance : impl_->instances) {
    splats |= instance.mesh->splats && instance.mesh->splats->size() > 0;
    surfaces |= !instance.mesh->indices.empty() || !instance.mesh->points.empty();
  }
  if (!(options.eye_dome_lighting >= 0.0f && options.eye_dome_lighting <= kMaxEyeDomeLighting))
    throw std::invalid_argument("eye-dome lighting: strength must lie between 0 and " +
                                std::to_string(static_cast<int>(kMaxEyeDomeLighting)));
  const bool eye_dome = options.eye_dome_lighting > 0.0f && surfaces;
  if ((splats && surfaces) || eye_dome) target.keep_depth(true);
  const std::vector<std::size_t> order = impl_->visible(frame);
  for (const std::size_t i : order) {
    const Mesh& mesh = *impl_->instances[i].mesh;
    if (options.wireframe || options.edges || impl_->instances[i].wireframe)
      detail::prepare_edges(impl_->prepared.at(&mesh), mesh);
    if (options.shading == Shading::flat) detail::prepare_face_normals(impl_->prepared.at(&mesh));
  }
  for (const std::size_t i : order) {
    const Instance& instance = impl_->instances[i];
    detail::draw_instance(renderer, target, frame, instance, impl_->prepared_of(instance), detail::DrawPass::opaque);
  }
  for (const std::size_t i : impl_->blended(frame, order)) {
    const Instance& instance = impl_->instances[i];
    detail::draw_instance(renderer, target, frame, instance, impl_->prepared_of(instance), detail::DrawPass::blended);
  }
  renderer.finish(target);
  if (eye_dome) detail::apply_eye_dome_lighting(renderer, target, view.clip_from_view, options.eye_dome_lighting);
  if (splats)
    for (const Instance& instance : impl_->instances)
      if (instance.mesh->splats) render_splats(renderer, target, view, *instance.mesh->splats, instance.world_from_object);
  return order.size();
}

bool sphere_in_frustum(const glm::mat4& clip_from_world, glm::vec3 center, float radius) {
  // Gribb-Hartmann: each frustum plane is the sum or difference of the matrix's last row and one other row.
  const auto row = [&](int r) {
    return glm::vec4(clip_from_world[0][r], clip_from_world[1][r], clip_from_world[2][r], clip_from_world[3][r]);
  };
  const glm::vec4 w = row(3);
  for (int axis = 0; axis < 3; ++axis) {
    for (const float sign : {1.0f, -1.0f}) {
      const glm::vec4 plane = w + sign * row(axis);
      const float length = glm::length(glm::vec3(plane));
      if (!(length > 0.0f)) continue;  // degenerate plane (e.g. an infinite far plane): rejects nothing
      if ((glm::dot(glm::vec3(plane), center) + plane.w) / length < -radius) return false;
    }
  }
  return true;
}

namespace {

// Row y of linear_depth.
void linear_depth_row(const Framebuffer& target, const glm::mat4& view_from_clip, int y, float* out) {
  const int width = target.width(), height = target.height();
  const std::span<const float> depth = target.depth();
  // Row 0 is the top of the image, ndc y = +1.
  const float ndc_y = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
  for (int x = 0; x < width; ++x) {
    const float d = depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
    if (!(d < 1.0f)) continue;
    const float ndc_x = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
    // The pixel's own x and y make this exact for off-centre projections too.
    const glm::vec4 view = view_from_clip * glm::vec4(ndc_x, ndc_y, 2.0f * d - 1.0f, 1.0f);
    out[x] = -view.z / view.w;
  }
}

}  // namespace

std::vector<float> linear_depth(const Framebuffer& target, const glm::mat4& clip_from_view) {
  const glm::mat4 view_from_clip = glm::inverse(clip_from_view);
  std::vector<float> out(static_cast<std::size_t>(target.width()) * static_cast<std::size_t>(target.height()), 0.0f);
  for (int y = 0; y < target.height(); ++y)
    linear_depth_row(target, view_from_clip, y, out.data() + static_cast<std::size_t>(y) * target.width());
  return out;
}

std::vector<float> linear_depth(Renderer& renderer, const Framebuffer& target, const glm::mat4& clip_from_view) {
  const glm::mat4 view_from_clip = glm::inverse(clip_from_view);
  std::vector<float> out(static_cast<std::size_t>(target.width()) * static_cast<std::size_t>(target.height()), 0.0f);
  renderer.parallel_for(static_cast<std::size_t>(target.height()), [&](std::size_t y) {
    linear_depth_row(target, view_from_clip, static_cast<int>(y), out.data() + y * static_cast<std::size_t>(target.width()));
  });
  return out;
}

}  // namespace facet
