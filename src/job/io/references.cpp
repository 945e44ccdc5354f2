// references.cpp - confinement of the files a model names to its folder tree, regular files only, bounded textures.
#include "job/io/references.hpp"

#include <algorithm>
#include <system_error>

#include "facet/error.hpp"
#include "facet/texture.hpp"
#include "core/file_util.hpp"
#include "job/io/loaders.hpp"
#include "scene/texture/image_decode.hpp"

namespace facet {

namespace fs = std::filesystem;

static_assert(LoadOptions{}.max_texture_size == kMaxTextureSize);

namespace {

// Whether `inner`, a normalised absolute path, is `outer` or lies below it.
bool lies_within(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // the empty element of a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

}  // namespace

Reference resolve_reference(const ReferencePolicy& policy, std::string_view name) {
  std::string written(name);
  std::replace(written.begin(), written.end(), '\\', '/');  // Windows separators, as in OBJ files made there
  const fs::path asked(written);
  const fs::path folder = policy.folder.empty() ? fs::path(".") : policy.folder;
  Reference out;
  fs::path candidate;
  if (policy.allow_external) {
    candidate = asked.is_absolute() ? asked : folder / asked;
  } else {
    const fs::path relative = asked.lexically_normal();
    const bool climbs = relative.empty() || *relative.begin() == "..";
    if (asked.is_absolute() || climbs) {
      if (!asked.has_filename()) {
        out.problem = "names no file";
        return out;
      }
      candidate = folder / asked.filename();
      out.note = "lies outside the model's folder; reading " + quoted(asked.filename()) +
                 " beside the model instead (" + setting("allow_external_files") + " reads it)";
    } else {
      candidate = folder / relative;
    }
  }
  candidate = candidate.lexically_normal();
  std::error_code ec;
  const fs::file_status status = fs::status(candidate, ec);
  if (!fs::exists(status)) {
    out.problem = "not found (looked for " + candidate.string() + ")";
    return out;
  }
  if (!fs::is_regular_file(status)) {
    out.problem = "not a regular file (" + candidate.string() + ")";
    return out;
  }
  if (!policy.allow_external) {
    // Links inside the folder may lead anywhere: the real path decides.
    std::error_code real_error, root_error;
    const fs::path real = fs::canonical(candidate, real_error);
    const fs::path root = fs::canonical(folder, root_error);
    if (real_error || root_error || !lies_within(real, root)) {
      out.problem = "leads outside the model's folder (" + candidate.string() + "); not read (" +
                    setting("allow_external_files") + " reads it)";
      return out;
    }
  }
  out.path = candidate;
  return out;
}

std::optional<std::string> usable_texture(const ReferencePolicy& policy, const LoadOptions& options,
                                          std::string_view name, const std::string& what, const std::string& source) {
  const Reference found = resolve_reference(policy, name);
  if (!found.note.empty()) warn(source, what + " " + printable(found.note));
  if (!found.path) {
    warn(source, what + ": " + printable(found.problem));
    return std::nullopt;
  }
  // The size from the header, read by the decoders that will decode it (image_decode.hpp); the file is read
  // through the same regular-file check as every other.
  std::optional<std::pair<int, int>> size;
  try {
    size = image_size(read_image_file(*found.path));
  } catch (const InputError& e) {
    warn(source, what + ": " + e.problem());
    return std::nullopt;
  }
  const int width = size ? size->first : 0, height = size ? size->second : 0;
  const bool known = size.has_value();
  // An unreadable header is reported when the image is decoded, as for any texture.
  if (known && (width > options.max_texture_size || height > options.max_texture_size)) {
    warn(source, what + " is " + std::to_string(width) + "x" + std::to_string(height) + " texels, over the limit of " +
                     std::to_string(options.max_texture_size) + " a side (" + setting("max_texture_size") +
                     "); drawn untextured");
    return std::nullopt;
  }
  return found.path->string();
}

}  // namespace facet
