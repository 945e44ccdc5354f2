// default_init.hpp - an allocator adaptor whose containers leave new elements default-initialised, not zeroed.
#pragma once

#include <memory>
#include <type_traits>
#include <utility>

namespace facet::detail {

// Base's allocation with construct() that default-initialises: resize() and emplace_back() with no arguments leave
// a trivially constructible element unset rather than zeroed. For arrays whose every element is written right
// after it is made (triangle setups written field by field, a mesh's scratch arrays): zeroing first would write
// every byte twice, and for a fresh allocation fault its pages in one pass earlier.
template <class Base>
struct DefaultInitAllocator : Base {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<typename std::allocator_traits<Base>::template rebind_alloc<U>>;
  };
  DefaultInitAllocator() = default;
  template <class Other>
  DefaultInitAllocator(const DefaultInitAllocator<Other>& other) noexcept : Base(static_cast<const Other&>(other)) {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace facet::detail
