// test_fuzz_regressions.cpp - every input that once broke a reader (tests/fuzz/regressions/FORMAT/) read again:
// each ends in a model or an InputError, quickly and with little memory. An input that is a few changed bytes of
// a file of Debian's assimp-testmodels is kept as NAME.patch, JSON naming that file and the bytes to change, so
// no third-party data lives in the tree.
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "facet/error.hpp"
#include "facet/view_spec.hpp"
#include "job/io/loaders.hpp"
#include "job/io/splat_loader.hpp"
#include "scene/texture/decode.hpp"

namespace facet::fuzz_regressions_tests {
namespace {

namespace fs = std::filesystem;

long peak_mib() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The input's bytes: the file, or for NAME.patch its base file with the patch's byte runs written over it.
std::string input_bytes(const fs::path& input) {
  if (input.extension() != ".patch") return file_bytes(input);
  const nlohmann::json spec = nlohmann::json::parse(file_bytes(input));
  std::string bytes = file_bytes(spec.at("base").get<std::string>());
  EXPECT_EQ(bytes.size(), spec.at("size").get<std::size_t>()) << input << ": its base file changed";
  for (const nlohmann::json& run : spec.at("patches")) {
    const auto offset = run.at(0).get<std::size_t>();
    const auto hex = run.at(1).get<std::string>();
    for (std::size_t k = 0; k + 1 < hex.size() && offset + k / 2 < bytes.size(); k += 2)
      bytes[offset + k / 2] = static_cast<char>(std::stoi(hex.substr(k, 2), nullptr, 16));
  }
  return bytes;
}

// Reads one input as the fuzz target of its folder does.
void read_as(const std::string& format, const fs::path& input) {
  std::string bytes = input_bytes(input);
  const LoadOptions options;
  const std::string source = input.string();
  if (format == "obj") (void)load_obj(input, bytes, source, options);
  else if (format == "ply") (void)load_ply(bytes, source, 2, 0);  // both PLY readers (loaders.hpp)
  else if (format == "stl") (void)load_stl(bytes, source);
  else if (format == "gltf") (void)load_gltf(input, bytes, source, options);
  else if (format == "pcd") (void)load_pcd(bytes, source);
  else if (format == "splat") (void)framing_of(load_splat(bytes, source), source);  // what refused the far one
  else if (format == "image")
    (void)decode_texture_file(std::span(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()),
                              TexelEncoding::srgb, input);
  else FAIL() << "no reader for the folder " << format;
}

TEST(FuzzRegressions, EveryInputEndsCleanly) {
  // The checkout, from the environment (ctest sets it): not compiled in, so the object is the same in every clone.
  const char* source = std::getenv("FACET_SOURCE_DIR");
  ASSERT_TRUE(source && *source) << "FACET_SOURCE_DIR must name the source tree (ctest sets it)";
  const fs::path root = fs::path(source) / "tests" / "fuzz" / "regressions";
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
}  // namespace facet::fuzz_regressions_tests
