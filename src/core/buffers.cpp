// buffers.cpp - large buffers on transparent huge pages: one fault per 2 MiB instead of one per 4 KiB.
#include <sys/mman.h>

#include <cstdlib>
#include <new>

#include "facet/framebuffer.hpp"

namespace facet::detail {

namespace {
constexpr std::size_t kLine = 64;
constexpr std::size_t kHugePage = std::size_t{2} << 20;
}  // namespace

void* allocate_buffer(std::size_t bytes) {
  const bool large = bytes >= kHugePage;
  const std::size_t alignment = large ? kHugePage : kLine;
  // aligned_alloc wants a multiple of the alignment; whole huge pages also keep the next block off the last one.
  const std::size_t size = ((bytes == 0 ? 1 : bytes) + alignment - 1) / alignment * alignment;
  void* p = std::aligned_alloc(alignment, size);
  if (!p) throw std::bad_alloc();
  // Only a hint: without transparent huge pages (or with them off) the memory is ordinary pages.
  if (large) ::madvise(p, size, MADV_HUGEPAGE);
  return p;
}

void free_buffer(void* p) noexcept { std::free(p); }

}  // namespace facet::detail
