// error.hpp - the exception facet throws for bad input: it names the file (or source) and what is wrong.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace facet {

// what() reads "<source>: <problem>", ready for the CLI's one-line "facet: error: ..." message.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& source, const std::string& problem)
      : std::runtime_error(source.empty() ? problem : source + ": " + problem), source_(source), problem_(problem) {}
  const std::string& source() const { return source_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string source_, problem_;
};

// How messages name a setting (a LoadOptions field, by its C++ name such as "max_triangles"): as
// "LoadOptions::max_triangles" unless a face has set its own spelling, once at start-up before any thread reports
// (the CLI its flag, "--max-triangles"; Python its keyword). So every face's users read the name they can pass.
using SettingSpelling = std::string (*)(std::string_view name);
void spell_settings(SettingSpelling spelling);
std::string setting(std::string_view name);

}  // namespace facet
