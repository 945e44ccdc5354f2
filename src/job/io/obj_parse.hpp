// obj_parse.hpp - the Wavefront OBJ text read into flat arrays: attributes, polygons, their materials.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace facet {

// One polygon corner as the file numbers it, zero-based after relative indices are resolved; -1 for "absent" (a
// texture coordinate or normal the corner does not name). A position index may be negative or past the end: the
// mesh builder reports those.
struct ObjCorner {
  std::int32_t v, vt, vn;
};

struct ObjData {
  std::vector<float> positions;  // x y z per `v`
  std::vector<float> colors;     // r g b per `v`, kept only when every `v` line has one
  std::vector<float> normals;    // x y z per `vn`
  std::vector<float> uvs;        // u v per `vt`
  std::vector<ObjCorner> corners;
  std::vector<std::uint32_t> face_ends;  // per polygon of 3+ corners: one past its last corner in `corners`
  std::vector<std::int32_t> face_materials;  // per polygon: the `usemtl` in force, -1 for none or unknown
  std::size_t dropped_faces = 0;             // `f` lines of fewer than three corners
};

// Called for each file an `mtllib` line names, in order, until one loads: appends its materials and their names
// (name -> index) and says whether the file was read.
using ObjMaterialReader = std::function<bool(const std::string& name, std::map<std::string, int>& names)>;

// Reads the OBJ text. Lines end at \n, \r\n or a lone \r; numbers are read as C's strtof would, a malformed one
// counting as 0 (and a colour that is not three numbers as no colour). Face, line and point indices that are 0 or
// not numbers, and positions spelled "nan" or "inf", are refused with an InputError(source, one-line problem) naming
// the line.
ObjData parse_obj(std::string_view text, const ObjMaterialReader& read_materials, const std::string& source);

}  // namespace facet
