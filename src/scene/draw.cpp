// draw.cpp - one instance: a draw per material group with the shader the shading mode picks, then edges or wireframe.
#include <algorithm>
#include <span>

#include "facet/color.hpp"
#include "facet/shaders/stock.hpp"
#include "scene/draw.hpp"

namespace facet::detail {
namespace {

struct GroupDraw {
  Renderer& renderer;
  Framebuffer& target;
  std::span<const MeshVertex> vertices;
  std::span<const std::uint32_t> indices;
  const RenderState& state;
  bool points = false;  // the indices name points, not triangles

  template <class S>
  void operator()(const S& shader) const {
    if (points) renderer.draw_points(target, shader, vertices, indices, state);
    else renderer.draw(target, shader, vertices, indices, state);
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

// The physically based inputs of a material, decoded to linear light; the base colour and its texture as
// `surface` has them (the options' colour override included).
PbrMaterial pbr_material(const Material& material, const SurfaceColor& surface) {
  PbrMaterial m;
  m.base_color = srgb_to_linear(surface.diffuse);
  m.metallic = material.metallic;
  m.roughness = material.roughness;
  m.emissive = material.emissive;
  m.occlusion_strength = material.occlusion_strength;
  m.dielectric_f0 = brdf::dielectric_f0(material.ior);
  m.specular = material.specular_factor;
  m.specular_color = material.specular_color_factor;
  m.face_colors = surface.face_colors;
  m.base_color_map = surface.texture;
  m.metallic_roughness_map = material.metallic_roughness_map.get();
  m.occlusion_map = material.occlusion_map.get();
  m.emissive_map = material.emissive_map.get();
  m.normal_map = material.normal_map.get();
  m.specular_map = material.specular_map.get();
  m.specular_color_map = material.specular_color_map.get();
  m.uv1_maps = material.uv1_maps;
  m.clearcoat = material.clearcoat;
  m.clearcoat_roughness = material.clearcoat_roughness;
  m.clearcoat_map = material.clearcoat_map.get();
  m.clearcoat_roughness_map = material.clearcoat_roughness_map.get();
  m.clearcoat_normal_map = material.clearcoat_normal_map.get();
  m.clearcoat_normal_scale = material.clearcoat_normal_scale;
  m.sheen_color = material.sheen_color;
  m.sheen_roughness = material.sheen_roughness;
  m.sheen_color_map = material.sheen_color_map.get();
  m.sheen_roughness_map = material.sheen_roughness_map.get();
  // Transmission shows through blending; an opaque or masked surface covers what is behind it whatever it says.
  if (material.alpha_mode == AlphaMode::blend) {
    m.transmission = material.transmission;
    m.transmission_map = material.transmission_map.get();
  }
  m.normal_scale = material.normal_scale;
  m.sampler = surface.sampler;
  m.opaque = surface.opaque;
  m.pyrender_lighting = material.pyrender_lighting;
  return m;
}

void draw_group(const GroupDraw& draw, const FrameContext& frame, const Instance& instance,
                const ObjectTransforms& transforms, const PreparedMesh& prepared, const TriangleGroup& group) {
  const SceneOptions& options = *frame.options;
  const Material& material = material_of(*instance.mesh, group);
  const SurfaceColor surface = surface_color(options, material, prepared, group);
  const Shading shading = shading_of(options, material);
  const bool masked = is_masked(options, material);
  switch (shading) {
    case Shading::automatic: {
      PbrShader shader;
      shader.transforms = transforms;
      shader.material = pbr_material(material, surface);
      shader.lights = frame.punctual;
      shader.ambient = frame.lights.ambient;
      shader.environment = options.environment.get();
      shader.eye = frame.eye;
      shader.tone_mapping = options.tone_mapping;
      shader.exposure = options.exposure;
      shader.normal_towards_eye = draw.points && !prepared.point_normals;
      // A blended surface lies in front of the opaque surfaces the occlusion was measured on.
      if (material.alpha_mode != AlphaMode::blend) {
        shader.screen_occlusion = frame.occlusion;
        shader.screen_occlusion_x = frame.occlusion_x;
        shader.screen_occlusion_y = frame.occlusion_y;
        shader.screen_occlusion_width = frame.occlusion_width;
        shader.screen_occlusion_height = frame.occlusion_height;
      }
      // An alpha-masked material takes the pixel's cotangent frame for its normal map, tangents or not.
      if (masked) {
        Masked<PbrShader> cut{shader};
        cut.alpha_cutoff = material.alpha_cutoff;
        draw(cut);
      } else if (!shader.material.textured()) {
        draw(UntexturedPbrShader{shader});
      } else if (prepared.tangents && shader.material.bumped()) {
        draw(TangentPbrShader{shader});
      } else {
        draw(shader);
      }
      break;
    }
    case Shading::blinn_phong:
    case Shading::phong: {
      const SpecularModel model = shading == Shading::phong ? SpecularModel::phong : SpecularModel::blinn_phong;
      SurfaceShader shader = lit_shader<SurfaceShader>(frame, transforms, surface, material, model);
      shader.normal_map = material.normal_map.get();
      shader.normal_scale = material.normal_scale;
      if (masked) {
        Masked<SurfaceShader> cut{shader};
        cut.alpha_cutoff = material.alpha_cutoff;
        draw(cut);
      } else if (!shader.surface.texture && !shader.normal_map) {
        draw(UntexturedSurfaceShader{shader});
      } else {
        draw(shader);
      }
      break;
    }
    case Shading::gouraud:
      draw(lit_shader<GouraudShader>(frame, transforms, surface, material, SpecularModel::blinn_phong));
      break;
    case Shading::flat: {
      FlatShader shader = lit_shader<FlatShader>(frame, transforms, surface, material, SpecularModel::blinn_phong);
      shader.face_normals = group.face_normals.data();
      draw(shader);
      break;
    }
    case Shading::unlit:
      if (masked) {
        Masked<UnlitShader> cut{UnlitShader{transforms.clip_from_object, surface}};
        cut.alpha_cutoff = material.alpha_cutoff;
        draw(cut);
      } else {
        draw(UnlitShader{transforms.clip_from_object, surface});
      }
      break;
    case Shading::normals: draw(NormalShader{transforms}); break;
    case Shading::depth:
      draw(DepthShader{transforms.clip_from_object, frame.view->view_from_world * instance.world_from_object,
                       frame.view->near, frame.view->far});
      break;
  }
}

}  // namespace

const Material& material_of(const Mesh& mesh, const TriangleGroup& group) {
  // Meshes without materials get the reference look of BENCHMARK.md section 7: white, specular 0.4, shininess 32.
  static const Material fallback{"default", glm::vec4(1.0f), glm::vec3(0.4f), 32.0f, {}};
  return group.material >= 0 ? mesh.materials[static_cast<std::size_t>(group.material)] : fallback;
}

RenderState surface_state(const SceneOptions& options, const Material& material, bool mirrored) {
  RenderState state;
  CullMode cull = options.cull;
  if (cull == CullMode::none && options.cull_single_sided && !material.double_sided) cull = CullMode::back;
  // A mirroring instance turns its front faces clockwise on screen; the side to cull turns with them.
  if (mirrored && cull != CullMode::none) cull = cull == CullMode::back ? CullMode::front : CullMode::back;
  state.cull = cull;
  if (options.painter) state.order = DrawOrder::back_to_front;
  if (options.painter || !options.depth_test) state.depth_func = DepthFunc::always;
  // Blended surfaces still write depth (as three.js does by default), so the depth, normal and id buffers show the
  // nearest surface whatever its material; their triangles are drawn farthest first.
  if (material.alpha_mode == AlphaMode::blend) {
    state.blend = BlendMode::alpha;
    state.order = DrawOrder::back_to_front;
  }
  return state;
}

SurfaceColor surface_color(const SceneOptions& options, const Material& material, const PreparedMesh& prepared,
                           const TriangleGroup& group) {
  return {options.color.value_or(material.diffuse), group.face_colors.empty() ? nullptr : group.face_colors.data(),
          group.material >= 0 ? prepared.textures[static_cast<std::size_t>(group.material)] : nullptr,
          material.sampler.value_or(options.sampler), material.alpha_mode == AlphaMode::opaque};
}

Shading shading_of(const SceneOptions& options, const Material& material) {
  return options.shading == Shading::automatic && material.unlit ? Shading::unlit : options.shading;
}

bool is_masked(const SceneOptions& options, const Material& material) {
  const Shading shading = shading_of(options, material);
  return material.alpha_mode == AlphaMode::mask && (shading == Shading::automatic || shading == Shading::phong ||
                                                    shading == Shading::blinn_phong || shading == Shading::unlit);
}

bool is_blended(const Mesh& mesh, const TriangleGroup& group) {
  return material_of(mesh, group).alpha_mode == AlphaMode::blend;
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

void draw_environment_background(Renderer& renderer, Framebuffer& target, const FrameContext& frame) {
  const SceneOptions& options = *frame.options;
  EnvironmentBackgroundShader shader;
  shader.world_from_clip = glm::inverse(frame.clip_from_world);
  shader.eye = frame.eye;
  shader.environment = options.environment.get();
  shader.blur = options.background_blur;
  shader.tone_mapping = options.tone_mapping;
  shader.exposure = options.exposure;
  static constexpr EnvironmentBackgroundShader::Vertex kCover[] = {{{-1.0f, -1.0f}}, {{3.0f, -1.0f}}, {{-1.0f, 3.0f}}};
  static constexpr std::uint32_t kIndices[] = {0, 1, 2};
  RenderState state;
  state.cull = CullMode::none;
  state.depth_test = false;
  state.depth_write = false;
  renderer.draw(target, shader, std::span<const EnvironmentBackgroundShader::Vertex>(kCover), kIndices, state);
}

namespace {

// The shading points are drawn with: the options' for surfaces, but unlit for a cloud without normals (there is no
// surface to light) and Gouraud for flat shading (a point has no face; lit once per point, as flat lights a face).
Shading point_shading(Shading shading, bool normals) {
  if (shading == Shading::normals || shading == Shading::depth || shading == Shading::unlit) return shading;
  if (!normals) return Shading::unlit;
  return shading == Shading::flat ? Shading::gouraud : shading;
}

// The mesh's points, in point_shading.
void draw_points(Renderer& renderer, Framebuffer& target, const FrameContext& frame, const Instance& instance,
                 const ObjectTransforms& transforms, const PreparedMesh& prepared) {
  const SceneOptions& options = *frame.options;
  RenderState state = surface_state(options, material_of(*instance.mesh, prepared.points), transforms.mirrored);
  state.point_size = options.point_size;
  state.point_shape = options.point_shape;
  // A length s at clip w spans s * P[1][1] / w of ndc's height 2, i.e. s * P[1][1] * height / (2 w) pixels.
  if (options.world_point_size)
    state.point_size_per_w =
        options.point_size * std::abs(frame.view->clip_from_view[1][1]) * static_cast<float>(target.height()) * 0.5f;
  const std::span<const MeshVertex> vertices(prepared.vertices);
  const GroupDraw draw{renderer, target, vertices, prepared.points.indices, state, true};
  // Points without normals are drawn unlit, but for pyrender's lighting, which lights them as facing the eye.
  const bool lit = prepared.point_normals || (options.shading == Shading::automatic &&
                                              material_of(*instance.mesh, prepared.points).pyrender_lighting);
  const Shading shading = point_shading(options.shading, lit);
  if (shading == options.shading) {
    draw_group(draw, frame, instance, transforms, prepared, prepared.points);
    return;
  }
  SceneOptions changed = options;
  changed.shading = shading;
  FrameContext changed_frame = frame;
  changed_frame.options = &changed;
  draw_group(draw, changed_frame, instance, transforms, prepared, prepared.points);
}

}  // namespace

void draw_instance(Renderer& renderer, Framebuffer& target, const FrameContext& frame, const Instance& instance,
                   const PreparedMesh& prepared, DrawPass pass) {
  const SceneOptions& options = *frame.options;
  const ObjectTransforms transforms = ObjectTransforms::make(frame.clip_from_world, instance.world_from_object);
  const std::span<const MeshVertex> vertices(prepared.vertices);

  const bool wireframe = options.wireframe || instance.wireframe;
  if (!wireframe) {
    for (const TriangleGroup& group : prepared.groups) {
      if (is_blended(*instance.mesh, group) != (pass == DrawPass::blended)) continue;
      const RenderState state = surface_state(options, material_of(*instance.mesh, group), transforms.mirrored);
      draw_group({renderer, target, vertices, group.indices, state}, frame, instance, transforms, prepared, group);
    }
  }
  if (pass == DrawPass::opaque && !prepared.points.indices.empty())
    draw_points(renderer, target, frame, instance, transforms, prepared);
  if (pass == DrawPass::blended || !(wireframe || options.edges) || prepared.edge_indices.empty()) return;

  RenderState lines;
  lines.cull = CullMode::none;
  lines.depth_test = options.depth_test;
  lines.line_width = options.line_width;
  glm::vec4 color = options.edge_color;
  if (wireframe) {
    color = options.color.value_or(glm::vec4(1.0f));
  } else {
    const glm::vec3 center(frame.view->view_from_world * instance.world_from_object * glm::vec4(prepared.center, 1));
    lines.depth_offset = edge_depth_offset(frame.view->clip_from_view, -center.z, frame.view->near, options.line_width,
                                           target.height(), prepared.radius * max_scale(instance.world_from_object));
  }
  renderer.draw_lines(target, LineShader{transforms.clip_from_object, color}, vertices, prepared.edge_indices, lines);
}

}  // namespace facet::detail
