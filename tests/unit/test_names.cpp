// test_names.cpp - the names every face spells the library's choices with (facet/names.hpp).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "facet/demo_scenes.hpp"
#include "facet/names.hpp"

namespace facet::names_tests {
namespace {

// Each name parses back to its value and each value has one name, so no face can spell a choice two ways.
template <class T>
void expect_one_name_each(std::span<const Named<T>> names) {
  std::set<std::string> seen;
  for (const Named<T>& n : names) {
    EXPECT_TRUE(seen.insert(n.name).second) << "twice: " << n.name;
    ASSERT_TRUE(parse_name(names, n.name).has_value()) << n.name;
    EXPECT_TRUE(*parse_name(names, n.name) == n.value) << n.name;
    EXPECT_STREQ(name_of(names, n.value), n.name);
  }
  EXPECT_FALSE(parse_name(names, "").has_value());
  EXPECT_FALSE(parse_name(names, "no such name").has_value());
}

TEST(Names, EveryChoiceHasOneName) {
  expect_one_name_each(shading_names());
  expect_one_name_each(cull_mode_names());
  expect_one_name_each(tone_mapping_names());
  expect_one_name_each(projection_names());
  expect_one_name_each(buffer_names());
  expect_one_name_each(demo_names());
  EXPECT_EQ(shading_names().size(), 8u);
  EXPECT_EQ(projection_names().size(), 10u);
}

TEST(Names, ShadingTakesTheCliSpellingAndPythonsFirstOne) {
  EXPECT_EQ(parse_shading("blinn-phong"), Shading::blinn_phong);
  EXPECT_EQ(parse_shading("blinn_phong"), Shading::blinn_phong);
  EXPECT_EQ(parse_shading("automatic"), Shading::automatic);
  EXPECT_FALSE(parse_shading("Blinn-Phong").has_value());
  EXPECT_FALSE(parse_shading("blinnphong").has_value());
  EXPECT_EQ(parse_projection("isometric"), Projection::isometric);
  EXPECT_FALSE(parse_projection("fisheye").has_value());
}

TEST(Names, BufferNamesAreBufferRequestsFields) {
  BufferRequest all{.color = false};
  for (const Named<bool BufferRequest::*>& n : buffer_names()) {
    BufferRequest request{.color = false};
    request.*n.value = true;
    EXPECT_EQ(request.color + request.depth + request.normal + request.ids + request.mask + request.motion, 1)
        << n.name;
    all.*n.value = true;
  }
  EXPECT_TRUE(all.color && all.depth && all.normal && all.ids && all.mask && all.motion);
}

TEST(Names, ListedJoinsTheNamesForMessages) {
  EXPECT_EQ(listed(cull_mode_names()), "back, front, none");
  EXPECT_EQ(listed(buffer_names()), "color, depth, normal, ids, mask, motion");
}

}  // namespace
}  // namespace facet::names_tests
