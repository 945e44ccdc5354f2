// warnings.hpp - where facet's warnings go: a model's recoverable problems, reported once each as "<file>: <problem>".
#pragma once

#include <string>
#include <vector>

namespace facet {

// Reports a warning: collected by the innermost WarningCapture alive on the calling thread, or else printed to
// standard error as "facet: warning: <message>".
void warn(const std::string& message);

// While alive, collects the warnings the calling thread reports instead of printing them, so a batch can put them
// in its report and a binding can raise them in its own way. Captures nest; each is for the thread that made it.
class WarningCapture {
 public:
  WarningCapture();
  ~WarningCapture();
  WarningCapture(const WarningCapture&) = delete;
  WarningCapture& operator=(const WarningCapture&) = delete;

  // The warnings collected so far, oldest first.
  const std::vector<std::string>& messages() const { return messages_; }

 private:
  friend void warn(const std::string& message);
  std::vector<std::string> messages_;
  WarningCapture* outer_ = nullptr;
};

}  // namespace facet
