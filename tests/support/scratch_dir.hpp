// scratch_dir.hpp - a fresh, empty folder per test under the build's test-output tree, for tests that write files.
#pragma once

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace facet::test {

// FACET_TEST_OUTPUT_DIR/AREA/Suite.Test, emptied first. Kept inside the build tree (not the system temp folder) so
// a failing test's files are there to inspect afterwards.
inline std::filesystem::path scratch_dir(const std::string& area) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(FACET_TEST_OUTPUT_DIR) / area / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace facet::test
