// image_asserts.hpp - comparing two framebuffers pixel for pixel, colour and depth bits alike.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cstddef>
#include <cstdint>

#include "facet/framebuffer.hpp"

namespace facet::test {

// Every pixel's colour and depth bits equal; a failure counts the differing pixels and names the first.
inline void expect_same(const Framebuffer& expected, const Framebuffer& actual, const char* what) {
  ASSERT_EQ(expected.color().size(), actual.color().size());
  std::size_t colour_diffs = 0, depth_diffs = 0, first = expected.color().size();
  for (std::size_t i = 0; i < expected.color().size(); ++i) {
    const bool colour = expected.color()[i] != actual.color()[i];
    const bool depth =
        std::bit_cast<std::uint32_t>(expected.depth()[i]) != std::bit_cast<std::uint32_t>(actual.depth()[i]);
    colour_diffs += colour;
    depth_diffs += depth;
    if ((colour || depth) && i < first) first = i;
  }
  EXPECT_EQ(colour_diffs, 0u) << what << ": first differing pixel " << first % expected.width() << ","
                              << first / expected.width() << std::hex << ", RGBA 0x"
                              << (first < expected.color().size() ? expected.color()[first] : 0u) << " expected, 0x"
                              << (first < actual.color().size() ? actual.color()[first] : 0u) << std::dec;
  EXPECT_EQ(depth_diffs, 0u) << what << ": first differing pixel " << first % expected.width() << ","
                             << first / expected.width();
}

}  // namespace facet::test
