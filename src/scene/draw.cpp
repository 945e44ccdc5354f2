// draw.cpp - one instance: a draw per material group with the shader the shading mode picks, then edges or wireframe.
#include <algorithm>
#include <span>

#include "facet/shaders/stock.hpp"
#include "scene/draw.hpp"

namespace facet::detail {
namespace {

// Meshes without materials get the reference look of BENCHMARK.md section 7: white, specular 0.4, shininess 32.
const Material& default_material() {
  static const Material material{"default", glm::vec4(1.0f), glm::vec3(0.4f), 32.0f, {}};
  return material;
}

struct GroupDraw {
  Renderer& renderer;
  Framebuffer& target;
  std::span<const MeshVertex> vertices;
  std::span<const std::uint32_t> indices;
  const RenderState& state;

  template <class S>
  void operator()(const S& shader) const {
    renderer.draw(target, shader, vertices, indices, state);
  }
};

template <class S>
S lit_shader(const FrameContext& frame, const ObjectTransforms& transforms, const SurfaceColor& surface,
             const Material& material, SpecularModel model) {
  S shader;
  shader.transforms = transforms;
  shader.surface = surface;
  shader.lights = frame.lights;
  shader.specular = material.specular;
  shader.shininess = material.shininess;
  shader.specular_model = model;
  shader.eye = frame.eye;
  return shader;
}

void draw_group(const GroupDraw& draw, const FrameContext& frame, const Instance& instance,
                const ObjectTransforms& transforms, const PreparedMesh& prepared, const TriangleGroup& group) {
  const SceneOptions& options = *frame.options;
  const auto index = static_cast<std::size_t>(group.material);
  const Material& material = group.material >= 0 ? instance.mesh->materials[index] : default_material();
  const SurfaceColor surface{
      options.color.value_or(material.diffuse), group.face_colors.empty() ? nullptr : group.face_colors.data(),
      group.material >= 0 ? prepared.textures[index] : nullptr, material.sampler.value_or(options.sampler)};
  const Shading shading = options.shading == Shading::automatic && material.unlit ? Shading::unlit : options.shading;
  switch (shading) {
    case Shading::automatic:
    case Shading::blinn_phong:
      draw(lit_shader<SurfaceShader>(frame, transforms, surface, material, SpecularModel::blinn_phong));
      break;
    case Shading::phong:
      draw(lit_shader<SurfaceShader>(frame, transforms, surface, material, SpecularModel::phong));
      break;
    case Shading::gouraud:
      draw(lit_shader<GouraudShader>(frame, transforms, surface, material, SpecularModel::blinn_phong));
      break;
    case Shading::flat: {
      FlatShader shader = lit_shader<FlatShader>(frame, transforms, surface, material, SpecularModel::blinn_phong);
      shader.face_normals = group.face_normals.data();
      draw(shader);
      break;
    }
    case Shading::unlit: draw(UnlitShader{transforms.clip_from_object, surface}); break;
    case Shading::normals: draw(NormalShader{transforms}); break;
    case Shading::depth:
      draw(DepthShader{transforms.clip_from_object, frame.view->view_from_world * instance.world_from_object,
                       frame.view->near, frame.view->far});
      break;
  }
}

}  // namespace

RenderState surface_state(const SceneOptions& options) {
  RenderState state;
  state.cull = options.cull;
  if (options.painter) state.order = DrawOrder::back_to_front;
  if (options.painter || !options.depth_test) state.depth_func = DepthFunc::always;
  return state;
}

float edge_depth_offset(const glm::mat4& clip_from_view, float distance, float near, float line_width,
                        int target_height, float radius) {
  const auto window_depth = [&](float d) {
    const glm::vec4 clip = clip_from_view * glm::vec4(0.0f, 0.0f, -d, 1.0f);
    return clip.z / clip.w * 0.5f + 0.5f;
  };
  distance = std::max(distance, 2.0f * near);
  // The pixel footprint at that distance, from two view-space points one unit apart vertically.
  const glm::vec4 a = clip_from_view * glm::vec4(0.0f, 0.0f, -distance, 1.0f);
  const glm::vec4 b = clip_from_view * glm::vec4(0.0f, 1.0f, -distance, 1.0f);
  const float pixels_per_unit = std::abs(b.y / b.w - a.y / a.w) * 0.5f * static_cast<float>(target_height);
  const float pixel = pixels_per_unit > 0.0f ? 1.0f / pixels_per_unit : 0.0f;
  // Two line widths of footprint cover a face sloping at up to ~75 degrees under the half-width of the line.
  float delta = 2.0f * std::max(line_width, 1.0f) * pixel + 1e-3f * radius;
  delta = std::min(delta, 0.5f * distance);
  const float offset = window_depth(distance - delta) - window_depth(distance);
  return std::clamp(offset, -0.05f, -1e-6f);
}

void draw_instance(Renderer& renderer, Framebuffer& target, const FrameContext& frame, const Instance& instance,
                   const PreparedMesh& prepared) {
  const SceneOptions& options = *frame.options;
  const ObjectTransforms transforms = ObjectTransforms::make(frame.clip_from_world, instance.world_from_object);
  const std::span<const MeshVertex> vertices(prepared.vertices);

  if (!options.wireframe) {
    const RenderState state = surface_state(options);
    for (const TriangleGroup& group : prepared.groups)
      draw_group({renderer, target, vertices, group.indices, state}, frame, instance, transforms, prepared, group);
  }
  if (!(options.wireframe || options.edges) || prepared.edge_indices.empty()) return;

  RenderState lines;
  lines.cull = CullMode::none;
  lines.depth_test = options.depth_test;
  lines.line_width = options.line_width;
  glm::vec4 color = options.edge_color;
  if (options.wireframe) {
    color = options.color.value_or(glm::vec4(1.0f));
  } else {
    const glm::vec3 center(frame.view->view_from_world * instance.world_from_object * glm::vec4(prepared.center, 1));
    lines.depth_offset = edge_depth_offset(frame.view->clip_from_view, -center.z, frame.view->near, options.line_width,
                                           target.height(), prepared.radius * max_scale(instance.world_from_object));
  }
  renderer.draw_lines(target, LineShader{transforms.clip_from_object, color}, vertices, prepared.edge_indices, lines);
}

}  // namespace facet::detail
