// fuzz_batch.cpp - libFuzzer target for `facet batch`'s jobs file: JSON lines of render flags, or model paths.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "batch_command.hpp"
#include "cli_options.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (std::filesystem::temp_directory_path() / "facet-fuzz-jobs.jsonl").string();
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, file);
    std::fclose(file);
  }
  facet::cli::BatchArgs args;
  args.jobs = path;
  args.output = "out/{stem}_{n}.png";
  return facet::fuzz::run([&] {
    try {
      (void)facet::cli::check_batch_jobs(args);
    } catch (const facet::cli::UsageError&) {
      // Two jobs writing one file, say: a usage error, reported as such.
    }
  });
}
