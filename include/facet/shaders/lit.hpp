// lit.hpp - LitUniforms: the material, light and camera uniforms the lit stock shaders (flat, Gouraud, surface) share.
#pragma once

#include <cmath>

#include "facet/fragment_lanes.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/surface_color.hpp"
#include "facet/simd.hpp"

namespace facet {

// A plain base struct, not an interface: each lit shader derives from it and adds its own Varyings, vertex() and
// fragment(), so the pipeline is still instantiated on one concrete type with no virtual call. The shaders differ
// only in where the normal comes from and whether lighting runs per vertex or per pixel.
struct LitUniforms {
  using Vertex = MeshVertex;
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;  // the uv derivatives pick the texture's mipmap level

  ObjectTransforms transforms{};
  SurfaceColor surface{};
  LightBlock lights{};
  glm::vec3 specular{0.0f};
  float shininess = 32.0f;
  SpecularModel specular_model = SpecularModel::blinn_phong;
  glm::vec3 eye{0.0f};  // world space

  // The surface colour at a pixel, for varyings that carry the vertex colour and uv.
  template <class V>
  glm::vec4 albedo(const Fragment<V>& f) const {
    return surface.albedo(f.varyings.color, f.primitive, f.varyings.uv, f.ddx.uv, f.ddy.uv);
  }
  // What the lights contribute at world point `world` with unit normal n; skips the specular pow() when the
  // material has no specular colour.
  LightTerms light_at(glm::vec3 n, glm::vec3 world) const {
    return light_terms(lights, n, world, eye - world, shininess, specular_model, specular != glm::vec3(0.0f));
  }
  // `albedo` lit at world point `world` with unit normal n; alpha passes through.
  glm::vec4 shade(glm::vec4 albedo, glm::vec3 n, glm::vec3 world) const {
    return glm::vec4(shade_lit(lights, glm::vec3(albedo), specular, shininess, specular_model, n, world, eye - world),
                     albedo.a);
  }

  // albedo() for 16 pixels (SurfaceColor::albedo_lanes).
  template <class V, class L>
  FACET_LANES_INLINE simd::ColorT<L> albedo_lanes(const FragmentLanes<V, L>& f) const {
    return surface.albedo_lanes(f);
  }

  // shade() for 16 pixels, the same operations in the same order as light_terms() and shade_lit(), so both give
  // identical images; the specular pow() is taken lane by lane with std::pow.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> shade_lanes(const simd::ColorT<L>& albedo, const simd::Vec3T<L>& n,
                                                 const simd::Vec3T<L>& world) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Vec3 v = normalize(eye - world);
    const bool with_specular = specular != glm::vec3(0.0f);
    Vec3 diffuse{splat<L>(lights.ambient.x), splat<L>(lights.ambient.y), splat<L>(lights.ambient.z)};
    Vec3 highlight{splat<L>(0.0f), splat<L>(0.0f), splat<L>(0.0f)};
    for (int i = 0; i < lights.count; ++i) {
      const glm::vec4 vk = lights.vector_kind[static_cast<std::size_t>(i)];
      const Vec3 l =
          vk.w == 0.0f ? Vec3{splat<L>(vk.x), splat<L>(vk.y), splat<L>(vk.z)} : normalize(glm::vec3(vk) - world);
      const Float n_dot_l = dot(n, l);
      const glm::vec3 c = lights.color[static_cast<std::size_t>(i)];
      const Float lambert = select(n_dot_l < 0.0f, splat<L>(0.0f), n_dot_l);  // std::max(n_dot_l, 0.0f)
      diffuse = diffuse + Vec3{lambert * c.x, lambert * c.y, lambert * c.z};
      if (!with_specular) continue;
      Float s;
      if (specular_model == SpecularModel::phong) {
        const Vec3 r = ((2.0f * n_dot_l) * n) - l;  // -l + 2 n.l n, as the scalar reflect
        s = dot(r, v);
      } else {
        s = dot(n, normalize(l + v));
      }
      s = select(s < 0.0f, splat<L>(0.0f), s);
      for (int k = 0; k < kLanes; ++k) s[k] = std::pow(s[k], shininess);
      highlight = highlight + Vec3{s * c.x, s * c.y, s * c.z};
    }
    return {albedo.r * diffuse.x + specular.x * highlight.x, albedo.g * diffuse.y + specular.y * highlight.y,
            albedo.b * diffuse.z + specular.z * highlight.z, albedo.a};
  }

  // The lanes whose surface is lit from behind: front_side() is false there.
  template <class L>
  FACET_LANES_INLINE simd::MaskT<L> back_lanes(const simd::MaskT<L>& front_facing) const {
    return transforms.mirrored ? front_facing : ~front_facing;
  }
};

}  // namespace facet
