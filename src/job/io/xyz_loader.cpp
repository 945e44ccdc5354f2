// xyz_loader.cpp - load_xyz(): point clouds as text, one point per line (.xyz, and Leica's .pts).
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

bool is_separator(char c) { return is_space(c) || c == ',' || c == ';'; }

// The numbers of one line, separated by spaces, tabs, commas or semicolons; false at the first that is not one.
bool read_numbers(std::string_view line, std::vector<double>& out, std::string_view& bad) {
  out.clear();
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && is_separator(line[i])) ++i;
    if (i == line.size()) return true;
    const std::size_t start = i;
    while (i < line.size() && !is_separator(line[i])) ++i;
    double value;
    const std::string_view token = line.substr(start, i - start);
    if (!parse_real(token, value)) {
      bad = token;
      return false;
    }
    out.push_back(value);
  }
}

// Whether columns [first, first + 3) of every row are unit vectors (normals) rather than colours.
bool unit_vectors(const std::vector<float>& values, std::size_t columns, std::size_t first) {
  for (std::size_t row = 0; row < values.size(); row += columns) {
    const double x = values[row + first], y = values[row + first + 1], z = values[row + first + 2];
    if (std::abs(std::sqrt(x * x + y * y + z * z) - 1.0) > 0.01) return false;
  }
  return true;
}

// Columns [first, first + 3) as colours: 0..255 if any exceeds 1, else 0..1.
void read_colors(const std::vector<float>& values, std::size_t columns, std::size_t first, Mesh& mesh) {
  double highest = 0.0;
  for (std::size_t row = 0; row < values.size(); row += columns)
    for (std::size_t c = 0; c < 3; ++c) highest = std::max(highest, double{values[row + first + c]});
  const double scale = highest > 1.0 ? 1.0 / 255.0 : 1.0;
  mesh.colors.reserve(values.size() / columns);
  for (std::size_t row = 0; row < values.size(); row += columns) {
    glm::vec4 color(1.0f);
    for (int c = 0; c < 3; ++c)
      color[c] = static_cast<float>(std::clamp(values[row + first + static_cast<std::size_t>(c)] * scale, 0.0, 1.0));
    mesh.colors.push_back(color);
  }
}

void read_normals(const std::vector<float>& values, std::size_t columns, std::size_t first, Mesh& mesh) {
  mesh.normals.reserve(values.size() / columns);
  for (std::size_t row = 0; row < values.size(); row += columns)
    mesh.normals.push_back(glm::vec3(values[row + first], values[row + first + 1], values[row + first + 2]));
}

}  // namespace

Mesh load_xyz(std::string_view text, const std::string& source) {
  // Every row's numbers, row after row; the first row sets how many a row has.
  std::vector<float> values;  // narrowed as read: a row of 3 numbers takes 12 bytes, its text at least 6
  std::vector<double> row;
  std::size_t columns = 0, line_number = 0, rows = 0;
  bool count_line_seen = false;
  std::string_view bad;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find_first_of("\r\n", at);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(at, end - at);
    at = end + 1;
    if (end < text.size() && text[end] == '\r' && at < text.size() && text[at] == '\n') ++at;
    ++line_number;
    std::size_t first = 0;
    while (first < line.size() && is_separator(line[first])) ++first;
    if (first == line.size() || line[first] == '#' || line.substr(first, 2) == "//") continue;
    const auto where = [&] { return "line " + std::to_string(line_number); };
    if (!read_numbers(line, row, bad)) throw InputError(source, where() + ": " + in_quotes(bad) + " is not a number");
    // A first row of one number is the point count (.pts writes one): the rows themselves are what is read.
    if (rows == 0 && row.size() == 1 && !count_line_seen) {
      count_line_seen = true;
      continue;
    }
    if (columns == 0) {
      if (row.size() < 3)
        throw InputError(source, where() + ": " + std::to_string(row.size()) + " numbers, not a point's x y z");
      columns = row.size();
    } else if (row.size() != columns) {
      throw InputError(source, where() + ": " + std::to_string(row.size()) + " numbers where the first point has " +
                                   std::to_string(columns));
    }
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(narrow(row[static_cast<std::size_t>(k)])))
        throw InputError(source, where() + ": the position is not finite");
    if (rows >= kMaxModelVertices) throw InputError(source, "more than 2^27 points");
    for (const double v : row) values.push_back(narrow(v));
    ++rows;
  }
  if (rows == 0) throw InputError(source, "nothing to draw (no points)");

  Mesh mesh;
  mesh.positions.reserve(rows);
  for (std::size_t r = 0; r < values.size(); r += columns)
    mesh.positions.push_back(glm::vec3(values[r], values[r + 1], values[r + 2]));
  // What the columns after x y z hold, by their count: 1 (intensity); 3 (normals when every row's are unit vectors,
  // else colours); 4 (.pts: intensity, then r g b); 6 (colours and normals, in whichever order the unit vectors say).
  const std::size_t extra = columns - 3;
  const auto read_intensities = [&] {
    mesh.intensities.reserve(rows);
    for (std::size_t r = 0; r < values.size(); r += columns) mesh.intensities.push_back(values[r + 3]);
  };
  if (extra == 1) {
    read_intensities();
  } else if (extra == 3) {
    if (unit_vectors(values, columns, 3)) read_normals(values, columns, 3, mesh);
    else read_colors(values, columns, 3, mesh);
  } else if (extra == 4) {
    read_intensities();
    read_colors(values, columns, 4, mesh);
  } else if (extra == 6) {
    const bool normals_first = unit_vectors(values, columns, 3);
    read_normals(values, columns, normals_first ? 3 : 6, mesh);
    read_colors(values, columns, normals_first ? 6 : 3, mesh);
  } else if (extra > 0) {
    warn(source, "ignored " + std::to_string(extra) + " column(s) after x y z (" + std::to_string(columns) +
                     " numbers per point: 3, 4, 6, 7 or 9 are understood)");
  }
  mesh.points_at_every_vertex();
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
