// references.hpp - the files a model names (MTL libraries, textures, glTF buffers, parts): where facet reads them.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace facet {

// Model files are untrusted: the files they name are read only from inside the model's folder tree unless the
// user allows external files.
struct ReferencePolicy {
  std::filesystem::path folder;  // the model's folder ("" for the current one)
  bool allow_external = false;
};

// Where a reference resolved to, or why nothing is read for it.
struct Reference {
  std::optional<std::filesystem::path> path;  // a regular file to read
  std::string problem;                        // when path is empty: "not found (looked for ...)", ...
  std::string note;                           // when the name was replaced: what was read instead, and why
};

// The file a model's reference `name` (as written: relative or absolute, '/' or '\' separators) is read from.
// Without allow_external: a name that is absolute or climbs out of the folder (../) is looked for by its file name
// in the model's folder instead, as viewers do for models made on another machine (`note` says so); and a file
// whose real path, links followed, lies outside the folder tree is not read. Only a regular file is ever read.
Reference resolve_reference(const ReferencePolicy& policy, std::string_view name);

}  // namespace facet
