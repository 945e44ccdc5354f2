// test_output_template.cpp - output file name templates: {model}, {stem}, {n}, {frame} and their widths.
#include <gtest/gtest.h>

#include <string>

#include "facet/output_template.hpp"

namespace facet::output_template_tests {
namespace {

TEST(OutputTemplate, FieldsTakeTheirValues) {
  const TemplateValues values{.model = "models/chair.v2.glb", .n = 7, .frame = 12};
  EXPECT_EQ(expand_template("thumbs/{stem}.png", values), "thumbs/chair.v2.png");
  EXPECT_EQ(expand_template("{model}.png", values), "chair.v2.glb.png");
  EXPECT_EQ(expand_template("{n:03}_{n}_{frame:04}_{frame:4}", values), "007_7_0012_0012");
  EXPECT_EQ(expand_template("{stem}{stem}", values), "chair.v2chair.v2");
}

TEST(OutputTemplate, OtherBracesStayAsWritten) {
  const TemplateValues values{.model = "a.obj"};
  EXPECT_EQ(expand_template("{frame}/{n}-{x}{stem", values), "{frame}/{n}-{x}{stem");
  EXPECT_EQ(expand_template("{{stem}}", values), "{a}");
  EXPECT_EQ(expand_template("{", values), "{");
  EXPECT_EQ(expand_template("", values), "");
  EXPECT_TRUE(template_has("out/{n:02}.png", "n"));
  EXPECT_TRUE(template_has("{{stem}}", "stem"));
  EXPECT_FALSE(template_has("out/{nn}.png", "n"));
  EXPECT_FALSE(template_has("out/{stem.png", "stem"));
}

}  // namespace
}  // namespace facet::output_template_tests
