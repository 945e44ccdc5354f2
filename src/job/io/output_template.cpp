// output_template.cpp - expanding {model}, {stem}, {n} and {frame} in output file names.
#include "facet/output_template.hpp"

#include <cctype>

namespace facet {
namespace {

// One field at `open` (a '{'): its name, width and the place after its '}', or nullopt when the text there is none.
struct Field {
  std::string_view name;
  int width = 0;
  std::size_t end = 0;
};

std::optional<Field> field_at(std::string_view text, std::size_t open) {
  std::size_t i = open + 1;
  while (i < text.size() && std::islower(static_cast<unsigned char>(text[i]))) ++i;
  Field field{text.substr(open + 1, i - open - 1), 0, 0};
  if (field.name != "model" && field.name != "stem" && field.name != "n" && field.name != "frame") return std::nullopt;
  if (i < text.size() && text[i] == ':') {
    ++i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && field.width < 100)
      field.width = field.width * 10 + (text[i++] - '0');
  }
  if (i >= text.size() || text[i] != '}') return std::nullopt;
  field.end = i + 1;
  return field;
}

std::string padded(long long number, int width) {
  std::string digits = std::to_string(number);
  if (static_cast<int>(digits.size()) < width) digits.insert(0, static_cast<std::size_t>(width) - digits.size(), '0');
  return digits;
}

// The field's text, or nullopt when it has no value.
std::optional<std::string> value_of(const Field& field, const TemplateValues& values) {
  if (field.name == "model" && values.model) return values.model->filename().string();
  if (field.name == "stem" && values.model) return values.model->stem().string();
  if (field.name == "n" && values.n) return padded(static_cast<long long>(*values.n), field.width);
  if (field.name == "frame" && values.frame) return padded(*values.frame, field.width);
  return std::nullopt;
}

}  // namespace

std::string expand_template(std::string_view pattern, const TemplateValues& values) {
  std::string out;
  std::size_t pos = 0;
  while (pos < pattern.size()) {
    const std::size_t open = pattern.find('{', pos);
    if (open == std::string_view::npos) break;
    out.append(pattern.substr(pos, open - pos));
    const std::optional<Field> field = field_at(pattern, open);
    const std::optional<std::string> value = field ? value_of(*field, values) : std::nullopt;
    if (value) {
      out += *value;
      pos = field->end;
    } else {
      out += '{';
      pos = open + 1;
    }
  }
  out.append(pattern.substr(std::min(pos, pattern.size())));
  return out;
}

bool template_has(std::string_view pattern, std::string_view name) {
  for (std::size_t open = pattern.find('{'); open != std::string_view::npos; open = pattern.find('{', open + 1))
    if (const std::optional<Field> field = field_at(pattern, open); field && field->name == name) return true;
  return false;
}

}  // namespace facet
