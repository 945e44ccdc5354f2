// load_problem.hpp - loader tests' shared steps: write a model file, load one that must be refused, cut one short.
#pragma once

#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "facet/error.hpp"
#include "facet/model_io.hpp"

namespace facet::test {

// Writes `bytes` to dir/name (creating folders on the way) and returns the path.
inline std::filesystem::path write_file(const std::filesystem::path& dir, const std::string& name,
                                        const std::string& bytes) {
  const std::filesystem::path p = dir / name;
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// Loads a file that must be refused; checks the error names the path on one line and returns its problem part.
inline std::string load_problem(const std::filesystem::path& p) {
  try {
    load_model(p);
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), p.string());
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.problem();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return {};
  }
  ADD_FAILURE() << "loading " << p << " did not throw";
  return {};
}

// Every prefix of a valid file, written to path, loads into a valid mesh (with triangles, or with Gaussian splats
// where `splats` is set) or throws InputError; never anything else. Warnings (skipped lines, dropped faces) are
// captured rather than printed.
inline void expect_every_prefix_loads_or_throws(const std::filesystem::path& path, const std::string& bytes,
                                                bool splats = false) {
  int loaded = 0, refused = 0;
  testing::internal::CaptureStderr();
  for (std::size_t n = 1; n < bytes.size(); ++n) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, n);
    try {
      const Mesh m = load_model(path);
      validate(m, path.string());
      if (splats) EXPECT_TRUE(m.splats);
      else EXPECT_GT(m.triangle_count(), 0u);
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), path.string());
      ++refused;
    }
  }
  testing::internal::GetCapturedStderr();
  EXPECT_GT(refused, 0);
  EXPECT_EQ(loaded + refused, static_cast<int>(bytes.size()) - 1);
}

}  // namespace facet::test
