// error.hpp - the exception facet throws for bad input: it names the file (or source) and what is wrong.
#pragma once

#include <stdexcept>
#include <string>

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

}  // namespace facet
