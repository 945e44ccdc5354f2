// warnings.cpp - warnings to the calling thread's capture, or to standard error.
#include "facet/warnings.hpp"

#include <cstdio>

namespace facet {

namespace {
thread_local WarningCapture* current_capture = nullptr;
}  // namespace

WarningCapture::WarningCapture() : outer_(current_capture) { current_capture = this; }

WarningCapture::~WarningCapture() { current_capture = outer_; }

void warn(const std::string& message) {
  if (current_capture) {
    current_capture->messages_.push_back(message);
    return;
  }
  // One fprintf: lines from threads warning at once do not interleave.
  std::fprintf(stderr, "facet: warning: %s\n", message.c_str());
}

}  // namespace facet
