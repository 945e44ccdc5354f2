// test_fuzz_regressions.cpp - every input that once broke a reader (tests/fuzz/regressions/FORMAT/) read again:
// each ends in a model or an InputError, quickly and with little memory.
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "facet/error.hpp"
#include "io/loaders.hpp"
#include "texture/decode.hpp"

namespace facet {
namespace {

namespace fs = std::filesystem;

long peak_mib() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

// Reads one input as the fuzz target of its folder does.
void read_as(const std::string& format, const fs::path& input) {
  std::ifstream in(input, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const LoadOptions options;
  const std::string source = input.string();
  if (format == "obj") (void)load_obj(input, bytes, source, options);
  else if (format == "ply") (void)load_ply(bytes, source);
  else if (format == "stl") (void)load_stl(bytes, source);
  else if (format == "gltf") (void)load_gltf(input, bytes, source, options);
  else if (format == "image")
    (void)decode_texture_file(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()),
                              TexelEncoding::srgb, input);
  else FAIL() << "no reader for the folder " << format;
}

TEST(FuzzRegressions, EveryInputEndsCleanly) {
  const fs::path root = fs::path(FACET_SOURCE_DIR) / "tests" / "fuzz" / "regressions";
  int inputs = 0;
  for (const fs::directory_entry& folder : fs::directory_iterator(root)) {
    if (!folder.is_directory() || folder.path().filename() == "batch") continue;  // jobs files: the CLI's tests
    for (const fs::directory_entry& input : fs::directory_iterator(folder.path())) {
      ++inputs;
      const long peak_before = peak_mib();
      const auto start = std::chrono::steady_clock::now();
      try {
        read_as(folder.path().filename().string(), input.path());
      } catch (const InputError&) {
        // The contract for bad input.
      }
      EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5)) << input.path();
      EXPECT_LT(peak_mib() - peak_before, 256) << input.path();
    }
  }
  EXPECT_GE(inputs, 1);
}

}  // namespace
}  // namespace facet
