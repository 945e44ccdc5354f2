// main.cpp - a user shader with a 16-lane fragment function: a shaded, colour-blended cube written to a PNG.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <facet/draw.hpp>
#include <facet/fragment_lanes.hpp>
#include <facet/framebuffer.hpp>
#include <facet/image_io.hpp>
#include <facet/renderer.hpp>
#include <facet/shader.hpp>
#include <facet/simd.hpp>

namespace {

// A plain struct, checked by the facet::Shader concept: a vertex type, the varyings (floats only, interpolated
// perspective-correctly), the uniforms as data members, and a vertex and a fragment function.
struct CubeShader {
  struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec3 color;
  };
  struct Varyings {
    glm::vec3 normal;  // world space
    glm::vec3 color;
  };
  static constexpr bool may_discard = false;  // lets the depth test run before shading, and allows lanes

  glm::mat4 clip_from_world{1.0f};
  glm::vec3 to_light = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));

  facet::VertexOut<Varyings> vertex(const Vertex& v) const {
    return {clip_from_world * glm::vec4(v.position, 1.0f), {v.normal, v.color}};
  }

  // The definition: half-Lambert lighting of the interpolated colour.
  glm::vec4 fragment(const facet::Fragment<Varyings>& f) const {
    const glm::vec3 n = glm::normalize(f.varyings.normal);
    const float light = 0.5f + 0.5f * glm::dot(n, to_light);
    return {f.varyings.color * light, 1.0f};
  }

  // The same on an 8x2 strip of pixels at once: the pipeline then shades 16 fragments per call. A template on the
  // lane layout L, so that each CPU level's copy of the pipeline holds the lanes in its own registers (one 512-bit,
  // two 256-bit or four 128-bit vectors per value); FACET_LANE_TYPES names that layout's Float, Vec3, Color, ...
  // Lane functions are always inlined (FACET_LANES_INLINE), since the pipeline compiles them into each level's tile
  // loop. No guard is needed: a fragment_lanes of the wrong shape, or on a shader that may discard, does not compile.
  template <class L>
  FACET_LANES_INLINE facet::simd::ColorT<L> fragment_lanes(const facet::FragmentLanes<Varyings, L>& f) const {
    using namespace facet::simd;
    FACET_LANE_TYPES(L);
    const Vec3 n = normalize(f.get(&Varyings::normal));
    const Float light = 0.5f + 0.5f * dot(n, to_light);
    const Vec3 color = f.get(&Varyings::color);
    return {color.x * light, color.y * light, color.z * light, splat<L>(1.0f)};
  }
};

// A unit cube, four vertices per face so that each face has its own normal; corners coloured by position.
void make_cube(std::vector<CubeShader::Vertex>& vertices, std::vector<std::uint32_t>& indices) {
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
      normal[axis] = side;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = side;  // u x v points along the normal, so the face winds counter-clockwise
      const auto first = static_cast<std::uint32_t>(vertices.size());
      for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        const glm::vec3 p = normal + c.x * u + c.y * v;
        vertices.push_back({p, normal, 0.5f + 0.5f * p});
      }
      for (const std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(first + i);
    }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT.png\n", argv[0]);
    return 2;
  }
  try {
    constexpr int width = 320, height = 240;
    std::vector<CubeShader::Vertex> vertices;
    std::vector<std::uint32_t> indices;
    make_cube(vertices, indices);

    CubeShader shader;
    const glm::mat4 view_from_world = glm::lookAt(glm::vec3(3.0f, 2.5f, 4.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
    const glm::mat4 clip_from_view =
        glm::perspective(glm::radians(40.0f), static_cast<float>(width) / height, 0.1f, 100.0f);
    shader.clip_from_world = clip_from_view * view_from_world;

    facet::Renderer renderer;  // every hardware thread
    facet::Framebuffer target(width, height);
    renderer.clear(target, {0.1f, 0.1f, 0.15f, 1.0f});
    renderer.draw(target, shader, std::span<const CubeShader::Vertex>(vertices), indices);
    renderer.finish(target);
    facet::write_png(argv[1], target);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "custom_shader: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
