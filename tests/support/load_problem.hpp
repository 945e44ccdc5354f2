// load_problem.hpp - loader tests' shared steps: write a model file, and load one that must be refused.
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

}  // namespace facet::test
