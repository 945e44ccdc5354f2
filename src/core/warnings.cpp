// warnings.cpp - warnings to the calling thread's capture, or to standard error; how messages name settings.
#include "facet/warnings.hpp"

#include <cstdio>

#include "facet/error.hpp"

namespace facet {

namespace {
thread_local WarningCapture* current_capture = nullptr;

std::string spell_as_field(std::string_view name) { return "LoadOptions::" + std::string(name); }
SettingSpelling setting_spelling = spell_as_field;
}  // namespace

void spell_settings(SettingSpelling spelling) { setting_spelling = spelling ? spelling : spell_as_field; }

std::string setting(std::string_view name) { return setting_spelling(name); }

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
