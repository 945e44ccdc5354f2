// test_allocations.cpp - steady-state frames allocate nothing on the heap (counted by a replaced operator new).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <new>

#include "support/draw_helpers.hpp"

// The replaced operator new takes its memory from malloc, so free() is the right way to release it; GCC cannot see
// that pairing through the replacement and would warn.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

// Replacing the global allocation functions counts every heap allocation in the process, any thread.
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// Every form is replaced, so that no allocation reaches the sanitizer's own operator new and is then freed here
// (std::stable_sort, for one, uses the nothrow form).
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept { return operator new(size, tag); }
void* operator new(std::size_t size, std::align_val_t align) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(align);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) { return operator new(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace facet::test::allocations_tests {
namespace {

TEST(Allocations, SteadyStateFramesDoNotTouchTheHeap) {
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 16.0f / 9.0f, 0.1f, 100.0f);
  const ClipMesh sphere = closed_sphere(180, 180, projection * glm::translate(glm::mat4(1), glm::vec3(0, 0, -3)));
  const std::vector<ColorShader::Vertex> vertices = color_vertices(sphere);
  Renderer renderer(2);
  Framebuffer fb(640, 360);
  ColorShader shader;
  RenderState painter;
  painter.order = DrawOrder::back_to_front;
  painter.depth_test = false;
  auto frame = [&](int f) {
    shader.clip_from_object = glm::rotate(glm::mat4(1), 0.02f * f, glm::vec3(0, 1, 0));
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    renderer.draw(fb, shader, std::span<const ColorShader::Vertex>(vertices), sphere.indices);
    renderer.draw(fb, shader, std::span<const ColorShader::Vertex>(vertices), sphere.indices, painter);
    renderer.finish(fb);
  };
  for (int f = 0; f < 3; ++f) frame(f);  // warm-up: buffers grow to their working size
  const long before = g_allocations.load();
  for (int f = 3; f < 8; ++f) frame(f);
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(renderer.last_stats().binned, 1000u);
}

}  // namespace
}  // namespace facet::test::allocations_tests
