// output_template.hpp - output file names from templates: {model}, {stem}, {n} and {frame}, as f3d spells them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace facet {

// The values a template's fields take; a field without a value stays as written.
struct TemplateValues {
  std::optional<std::filesystem::path> model{};  // {model}: its file name ("chair.glb"); {stem}: without the extension
  std::optional<std::size_t> n{};                // {n}: the model's place in the list, from 0
  std::optional<int> frame{};                    // {frame}: the frame number
};

// `pattern` with every field replaced. Numbers take an optional zero-padded width: {n:03}, {frame:04} ({frame:4}
// pads alike). Braces that hold no field, or a field without a value, are kept as written.
std::string expand_template(std::string_view pattern, const TemplateValues& values);

// Whether `pattern` holds the field `name` ("model", "stem", "n" or "frame"), with or without a width.
bool template_has(std::string_view pattern, std::string_view name);

}  // namespace facet
