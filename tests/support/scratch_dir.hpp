// scratch_dir.hpp - a fresh, empty folder per test under the build's test-output tree, for tests that write files.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace facet::test {

// The environment's FACET_TEST_OUTPUT_DIR, or test-output in the working folder (build/tests under ctest): inside
// the build tree rather than the system's temporary folder, so that a failing test's files are there to inspect.
inline std::filesystem::path test_output_root() {
  const char* dir = std::getenv("FACET_TEST_OUTPUT_DIR");
  return dir && *dir ? std::filesystem::path(dir) : std::filesystem::current_path() / "test-output";
}

// test_output_root()/AREA/Suite.Test, emptied first.
inline std::filesystem::path scratch_dir(const std::string& area) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      test_output_root() / area / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace facet::test
