// fuzz_environment.cpp - libFuzzer target for the environment image reader: Radiance .hdr (stb_image) and OpenEXR
// (OpenEXR's C core). The reader takes a path and goes by its extension, so the input is written to a file: its
// first byte picks the extension (even: .hdr, odd: .exr), the rest is the file.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "facet/environment.hpp"
#include "fuzz_input.hpp"

namespace {

// A folder of this process's own (libFuzzer's -jobs run several), removed at exit.
struct Folder {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("facet-fuzz-environment-" + std::to_string(::getpid()));
  Folder() { std::filesystem::create_directories(path); }
  ~Folder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

const std::filesystem::path& input_path(bool exr) {
  static const Folder folder;
  static const std::filesystem::path hdr = folder.path / "input.hdr", openexr = folder.path / "input.exr";
  return exr ? openexr : hdr;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::filesystem::path& path = input_path(data[0] & 1);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!out) std::abort();  // the fuzzer's own failure, not the reader's
  }
  return facet::fuzz::run([&] { (void)facet::read_environment_image(path); });
}
