// in_parts.hpp - work split into a few parts run on threads of their own, for one-off passes outside the renderer's
// pool (mesh preparation, environment prefiltering).
#pragma once

#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace facet::detail {

// Calls part(p) for every p in [0, parts), each on its own thread (the caller's the first), and rethrows the first
// part's exception once all have returned. The browser build calls them in turn.
template <class Part>
void in_parts(int parts, Part&& part) {
  if (parts <= 1) return part(0);
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(parts));
  const auto guarded = [&](int p) {
    try {
      part(p);
    } catch (...) {
      errors[static_cast<std::size_t>(p)] = std::current_exception();
    }
  };
#if defined(__EMSCRIPTEN__)
  for (int p = 0; p < parts; ++p) guarded(p);
#else
  {
    std::vector<std::jthread> helpers;
    helpers.reserve(static_cast<std::size_t>(parts - 1));
    for (int p = 1; p < parts; ++p) helpers.emplace_back(guarded, p);
    guarded(0);
  }
#endif
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

// Part p of `parts` equal ranges of [0, count).
inline std::size_t part_begin(std::size_t count, int p, int parts) {
  return count * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts);
}

}  // namespace facet::detail
