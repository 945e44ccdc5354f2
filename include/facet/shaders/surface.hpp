// surface.hpp - SurfaceShader: per-pixel Phong or Blinn-Phong lighting of a textured, vertex-coloured material.
#pragma once

#include <algorithm>
#include <cmath>

#include "facet/fragment_lanes.hpp"
#include "facet/shaders/lit.hpp"
#include "facet/simd.hpp"

namespace facet {

// With one white directional light, ambient 0.15, specular 0.4, shininess 32 and SpecularModel::phong this is the
// reference fragment shader of BENCHMARK.md section 7.
struct SurfaceShader : LitUniforms {
  struct Varyings {
    glm::vec3 world;
    glm::vec3 normal;  // world space, not normalized until the pixel
    glm::vec4 color;
    glm::vec2 uv;
  };

  // A tangent-space normal map, or null; its frame comes from the screen-space derivatives of the world position
  // and the uvs (a cotangent frame, as in Schueler's "Normal Mapping without Precomputed Tangents"), so meshes need
  // no tangents.
  const Texture* normal_map = nullptr;
  float normal_scale = 1.0f;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p,
            {glm::vec3(transforms.world_from_object * p), transforms.normal_from_object * v.normal, v.color, v.uv}};
  }
  // Back faces are lit with the normal reversed (two-sided lighting, as glTF asks of double-sided materials).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    glm::vec3 n = glm::normalize(f.varyings.normal);
    if (!transforms.front_side(f.front_facing)) n = -n;
    if (normal_map) n = mapped_normal(n, f);
    return shade(albedo(f), n, f.varyings.world);
  }

  // fragment() for 16 pixels at once, the same operations in the same order, so both give identical images.
  // Texture samples and the specular pow() are taken lane by lane with the scalar functions; a normal-mapped
  // material is shaded by fragment() lane by lane.
  FACET_LANES_INLINE simd::Color fragment_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    if (normal_map) {
      Color out;
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec4 c = fragment(f.lane(k));
        out.r[k] = c.r, out.g[k] = c.g, out.b[k] = c.b, out.a[k] = c.a;
      }
      return out;
    }
    Vec3 n = normalize(f.get(&Varyings::normal));
    // front_side(): front_facing != mirrored; the normal is reversed where that is false.
    const Mask back = transforms.mirrored ? f.front_facing : ~f.front_facing;
    n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
    const Color albedo = albedo_lanes(f);
    const Vec3 world = f.get(&Varyings::world);
    const Vec3 v = normalize(eye - world);
    const bool with_specular = specular != glm::vec3(0.0f);
    Vec3 diffuse{splat(lights.ambient.x), splat(lights.ambient.y), splat(lights.ambient.z)};
    Vec3 highlight{splat(0.0f), splat(0.0f), splat(0.0f)};
    for (int i = 0; i < lights.count; ++i) {
      const glm::vec4 vk = lights.vector_kind[static_cast<std::size_t>(i)];
      const Vec3 l = vk.w == 0.0f ? Vec3{splat(vk.x), splat(vk.y), splat(vk.z)} : normalize(glm::vec3(vk) - world);
      const Float n_dot_l = dot(n, l);
      const glm::vec3 c = lights.color[static_cast<std::size_t>(i)];
      const Float lambert = select(n_dot_l < 0.0f, splat(0.0f), n_dot_l);  // std::max(n_dot_l, 0.0f)
      diffuse = diffuse + Vec3{lambert * c.x, lambert * c.y, lambert * c.z};
      if (!with_specular) continue;
      Float s;
      if (specular_model == SpecularModel::phong) {
        const Vec3 r = ((2.0f * n_dot_l) * n) - l;  // -l + 2 n.l n, as the scalar reflect
        s = dot(r, v);
      } else {
        s = dot(n, normalize(l + v));
      }
      s = select(s < 0.0f, splat(0.0f), s);
      for (int k = 0; k < kLanes; ++k) s[k] = std::pow(s[k], shininess);
      highlight = highlight + Vec3{s * c.x, s * c.y, s * c.z};
    }
    return {albedo.r * diffuse.x + specular.x * highlight.x, albedo.g * diffuse.y + specular.y * highlight.y,
            albedo.b * diffuse.z + specular.z * highlight.z, albedo.a};
  }

  // surface.albedo() lane by lane: diffuse x vertex colour x face colour x texture, alpha 1 when opaque.
  FACET_LANES_INLINE simd::Color albedo_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    const Color vertex = f.get(&Varyings::color);
    const glm::vec4 d = surface.diffuse;
    Color c{d.r * vertex.r, d.g * vertex.g, d.b * vertex.b, d.a * vertex.a};
    if (surface.face_colors) {
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec4 face = surface.face_colors[f.primitive[k]];
        c.r[k] *= face.r, c.g[k] *= face.g, c.b[k] *= face.b, c.a[k] *= face.a;
      }
    }
    if (surface.texture) {
      const Vec2 uv = f.get(&Varyings::uv);
      const std::size_t u = FragmentLanes<Varyings>::float_index(&Varyings::uv);
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec4 t =
            surface.texture->sample(glm::vec2(uv.x[k], uv.y[k]), glm::vec2(f.ddx[u][k], f.ddx[u + 1][k]),
                                    glm::vec2(f.ddy[u][k], f.ddy[u + 1][k]), surface.sampler);
        c.r[k] *= t.r, c.g[k] *= t.g, c.b[k] *= t.b, c.a[k] *= t.a;
      }
    }
    if (surface.opaque) c.a = splat(1.0f);
    return c;
  }

  glm::vec3 mapped_normal(glm::vec3 n, const Fragment<Varyings>& f) const {
    // Window y grows downwards; the frame is built for y up, as OpenGL's dFdy gives it.
    const glm::vec3 dp1 = f.ddx.world, dp2 = -f.ddy.world;
    const glm::vec2 duv1 = f.ddx.uv, duv2 = -f.ddy.uv;
    const glm::vec3 dp2perp = glm::cross(dp2, n), dp1perp = glm::cross(n, dp1);
    const glm::vec3 t = dp2perp * duv1.x + dp1perp * duv2.x, b = dp2perp * duv1.y + dp1perp * duv2.y;
    const float extent = std::max(glm::dot(t, t), glm::dot(b, b));
    if (!(extent > 0.0f) || !std::isfinite(extent)) return n;  // uvs constant over the pixel: no frame
    const float scale = 1.0f / std::sqrt(extent);
    const glm::vec3 texel = glm::vec3(normal_map->sample(f.varyings.uv, f.ddx.uv, f.ddy.uv, surface.sampler));
    const glm::vec3 m = texel * 2.0f - 1.0f;
    const glm::vec3 mapped = t * (scale * m.x * normal_scale) + b * (scale * m.y * normal_scale) + n * m.z;
    const float length = glm::length(mapped);
    return length > 0.0f && std::isfinite(length) ? mapped / length : n;
  }
};

// SurfaceShader for a material with neither texture nor normal map: the same picture without the screen-space
// derivatives, which only texture level of detail and the normal map's frame read. Interpolating them triples
// the work per varying in the tile loop.
struct UntexturedSurfaceShader : SurfaceShader {
  static constexpr bool needs_derivatives = false;
};

}  // namespace facet
