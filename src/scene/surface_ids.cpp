// surface_ids.cpp - the id pass (which instance and triangle each pixel shows) and the normals read back from it.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "facet/shaders/stock.hpp"
#include "scene/pixel_ray.hpp"
#include "scene/scene_impl.hpp"

namespace facet {
namespace {

// A 32-bit key as the RGBA8 colour that packs back to exactly it: each byte b becomes b / 255, which
// pack_channel rounds back to b (interpolating the white vertex colour leaves the product within 1e-7 of it).
glm::vec4 color_of_key(std::uint32_t key) {
  return glm::vec4(static_cast<float>(key & 0xff), static_cast<float>((key >> 8) & 0xff),
                   static_cast<float>((key >> 16) & 0xff), static_cast<float>(key >> 24)) /
         255.0f;
}

}  // namespace

SurfaceIds Scene::render_ids(Renderer& renderer, Framebuffer& target, const View& view, const SceneOptions& options) {
  const detail::FrameContext frame = detail::frame_context(view, options);
  const std::vector<std::size_t> order = impl_->visible(frame);

  // Keys number the drawn triangles in drawing order; key k is triangle key_triangle[k] of key_instance[k].
  std::vector<std::uint32_t> key_instance, key_triangle;
  std::size_t keys = 0;
  for (const std::size_t i : order)
    for (const detail::TriangleGroup& group : impl_->prepared_of(impl_->instances[i]).groups)
      keys += group.triangle_count();
  if (keys >= kNoSurface) throw std::length_error("render_ids: more triangles than 32-bit ids can number");
  key_instance.reserve(keys);
  key_triangle.reserve(keys);

  target.keep_samples(true);                      // sample 0 is read below
  renderer.clear(target, glm::vec4(1.0f), 1.0f);  // every byte 0xff: kNoSurface
  std::vector<MeshVertex> white;
  // Every draw's face colours, the keys in order: each draw reads its own stretch until the frame is drawn.
  std::vector<glm::vec4> key_colors;
  key_colors.reserve(keys);
  // As render() draws: the opaque surfaces, then the blended ones farthest first, each with its material's state
  // but no blending, so each pixel keeps the key of the nearest surface.
  const auto draw = [&](std::size_t i, bool blended) {
    const Instance& instance = impl_->instances[i];
    const detail::PreparedMesh& prepared = impl_->prepared_of(instance);
    // Positions only: the vertex colour white and no texture leave the face colour, the key, as the albedo.
    white.resize(prepared.vertices.size());
    std::transform(prepared.vertices.begin(), prepared.vertices.end(), white.begin(),
                   [](const MeshVertex& v) { return MeshVertex{v.position}; });
    const ObjectTransforms transforms = ObjectTransforms::make(frame.clip_from_world, instance.world_from_object);
    for (const detail::TriangleGroup& group : prepared.groups) {
      if (detail::is_blended(*instance.mesh, group) != blended) continue;
      const glm::vec4* group_keys = key_colors.data() + key_colors.size();
      for (std::size_t k = 0; k < group.triangle_count(); ++k) {
        key_colors.push_back(color_of_key(static_cast<std::uint32_t>(key_instance.size())));
        key_instance.push_back(static_cast<std::uint32_t>(i));
        key_triangle.push_back(group.triangle(k));
      }
      const Material& material = detail::material_of(*instance.mesh, group);
      RenderState state = detail::surface_state(options, material, transforms.mirrored);
      state.blend = BlendMode::none;
      const std::span<const std::uint32_t> indices(group.indices);
      if (detail::is_masked(options, material)) {
        // Cut by the alpha the colour pass cuts by: the real vertices and albedo, the key written where kept.
        Masked<UnlitShader> shader{
            UnlitShader{transforms.clip_from_object, detail::surface_color(options, material, prepared, group)}};
        shader.alpha_cutoff = material.alpha_cutoff;
        shader.replace = group_keys;
        renderer.draw(target, shader, std::span<const MeshVertex>(prepared.vertices), indices, state);
      } else {
        const UnlitShader shader{transforms.clip_from_object,
                                 SurfaceColor{glm::vec4(1.0f), group_keys, nullptr, {}}};
        renderer.draw(target, shader, std::span<const MeshVertex>(white), indices, state);
      }
    }
  };
  for (const std::size_t i : order) draw(i, false);
  for (const std::size_t i : impl_->blended(frame, order)) draw(i, true);
  renderer.finish(target);

  SurfaceIds ids{target.width(), target.height(), {}, {}};
  const std::size_t pixels = static_cast<std::size_t>(ids.width) * ids.height;
  ids.instance.assign(pixels, kNoSurface);
  ids.triangle.assign(pixels, kNoSurface);
  // Sample 0 with multisampling: an average of ids is no id.
  const std::span<const std::uint32_t> color = target.sample_color(0);
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::uint32_t key = color[p];
    if (key >= key_instance.size()) continue;
    ids.instance[p] = key_instance[key];
    ids.triangle[p] = key_triangle[key];
  }
  return ids;
}

std::vector<glm::vec3> Scene::camera_normals(const SurfaceIds& ids, const View& view) const {
  const std::size_t pixels = static_cast<std::size_t>(ids.width) * ids.height;
  if (ids.instance.size() != pixels || ids.triangle.size() != pixels)
    throw std::invalid_argument("camera_normals: ids do not match their size");
  std::vector<glm::vec3> normals(pixels, glm::vec3(0.0f));

  // Each mesh triangle's corners among the prepared vertices (whose normals are the ones shaded with).
  std::unordered_map<const detail::PreparedMesh*, std::vector<const std::uint32_t*>> corners_of;
  const auto corners = [&](const detail::PreparedMesh& prepared) -> const std::vector<const std::uint32_t*>& {
    auto [it, added] = corners_of.try_emplace(&prepared);
    if (added)
      for (const detail::TriangleGroup& group : prepared.groups) {
        for (std::size_t k = 0; k < group.triangle_count(); ++k) {
          const std::uint32_t t = group.triangle(k);
          if (it->second.size() <= t) it->second.resize(t + 1, nullptr);
          it->second[t] = &group.indices[3 * k];
        }
      }
    return it->second;
  };

  const detail::PixelRays rays(view.clip_from_view, ids.width, ids.height);
  // The instance of the previous pixel, whose matrices and corner table are at hand.
  std::uint32_t current = kNoSurface;
  const detail::PreparedMesh* prepared = nullptr;
  const std::vector<const std::uint32_t*>* table = nullptr;
  glm::mat4 view_from_object{1.0f};
  glm::mat3 normal_from_object{1.0f};
  bool mirrored = false;
  for (int y = 0; y < ids.height; ++y) {
    for (int x = 0; x < ids.width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * ids.width + x;
      if (ids.instance[p] >= impl_->instances.size()) continue;
      if (ids.instance[p] != current) {
        current = ids.instance[p];
        const Instance& instance = impl_->instances[current];
        prepared = &impl_->prepared_of(instance);
        table = &corners(*prepared);
        view_from_object = view.view_from_world * instance.world_from_object;
        normal_from_object = glm::transpose(glm::inverse(glm::mat3(view_from_object)));
        mirrored = glm::determinant(glm::mat3(instance.world_from_object)) < 0.0f;
      }
      if (ids.triangle[p] >= table->size() || !(*table)[ids.triangle[p]]) continue;
      const std::uint32_t* corner = (*table)[ids.triangle[p]];
      glm::vec3 q[3], n[3];
      for (int k = 0; k < 3; ++k) {
        const MeshVertex& v = prepared->vertices[corner[k]];
        q[k] = glm::vec3(view_from_object * glm::vec4(v.position, 1.0f));
        n[k] = v.normal;
      }
      // The pixel centre's ray meets the triangle's plane at barycentric (1 - u - w, u, w).
      const detail::PixelRays::Ray ray = rays.at(x, y);
      const glm::vec2 b = ray_barycentric(ray, q);
      const glm::vec3 object_normal = (1.0f - b.x - b.y) * n[0] + b.x * n[1] + b.y * n[2];
      const glm::vec3 normal = normal_from_object * object_normal;
      const float length = glm::length(normal);
      const glm::vec3 unit = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
      // The stock shaders light a back face with the normal reversed; so does this buffer. The triangle faces the
      // camera when its corners run counter-clockwise as the ray sees them; a mirroring instance swaps its sides.
      const bool facing = glm::dot(glm::cross(q[1] - q[0], q[2] - q[0]), ray.direction) < 0.0f;
      normals[p] = facing != mirrored ? unit : -unit;
    }
  }
  return normals;
}

}  // namespace facet
