// thumbnail.cpp - one freedesktop thumbnail: the input's URI made a path, the model rendered to fill a square, the
// PNG written with the specification's metadata.
#include "facet/thumbnail.hpp"

#include <sys/stat.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/file_util.hpp"
#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/version.hpp"

namespace facet {
namespace {

constexpr std::array kTypes{
    // In Debian's shared-mime-info database.
    ModelMimeType{"model/gltf-binary", "*.glb"},
    ModelMimeType{"model/gltf+json", "*.gltf"},
    ModelMimeType{"model/obj", "*.obj"},
    ModelMimeType{"model/stl", "*.stl"},
    ModelMimeType{"model/3mf", "*.3mf"},
    ModelMimeType{"image/x-3ds", "*.3ds"},
    ModelMimeType{"image/x-lwo", "*.lwo"},
    // Not in it: f3d's names where f3d has one, else IANA's registered one, else an x- name.
    ModelMimeType{"application/vnd.ply", "*.ply", true},
    ModelMimeType{"application/vnd.fbx", "*.fbx", true},
    ModelMimeType{"application/vnd.dae", "*.dae", true},
    ModelMimeType{"application/vnd.off", "*.off", true},
    ModelMimeType{"application/vnd.pts", "*.pts", true},
    ModelMimeType{"model/x3d+xml", "*.x3d", true},
    ModelMimeType{"application/x-pcd", "*.pcd", true},
    ModelMimeType{"application/x-xyz", "*.xyz", true},
    ModelMimeType{"application/x-splat", "*.splat", true},
};

bool starts_with_nocase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
  return true;
}

// A URI's scheme: letters, digits, '+', '-', '.' after a letter, then ':' and "//".
bool has_scheme(std::string_view text) {
  const std::size_t colon = text.find(':');
  if (colon == 0 || colon == std::string_view::npos || !std::isalpha(static_cast<unsigned char>(text[0])))
    return false;
  for (std::size_t i = 0; i < colon; ++i) {
    const char c = text[i];
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return text.substr(colon + 1).starts_with("//");
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

void check_size(int size) {
  if (size < 1 || size > kMaxThumbnailSize)
    throw std::invalid_argument("size: must lie in 1.." + std::to_string(kMaxThumbnailSize) + " pixels");
}

}  // namespace

std::filesystem::path path_of_uri(std::string_view input) {
  const std::string source(input);
  if (!starts_with_nocase(input, "file:")) {
    if (has_scheme(input)) throw InputError(source, "not a local file: only file:// URIs and paths are read");
    return std::filesystem::path(source);
  }
  std::string_view rest = input.substr(5);
  if (rest.starts_with("//")) {
    rest.remove_prefix(2);
    const std::size_t slash = rest.find('/');
    const std::string_view host = rest.substr(0, slash);
    if (!host.empty() && !starts_with_nocase(host, "localhost"))
      throw InputError(source, "not a local file: the URI names host '" + std::string(host) + "'");
    if (slash == std::string_view::npos) throw InputError(source, "the URI names no path");
    rest.remove_prefix(slash);
  }
  if (!rest.starts_with('/')) throw InputError(source, "a file URI's path must be absolute");
  std::string path;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] != '%') {
      path += rest[i];
      continue;
    }
    const int high = i + 2 < rest.size() ? hex_digit(rest[i + 1]) : -1;
    const int low = i + 2 < rest.size() ? hex_digit(rest[i + 2]) : -1;
    if (high < 0 || low < 0) throw InputError(source, "bad percent escape at character " + std::to_string(i + 6));
    if (high == 0 && low == 0) throw InputError(source, "the URI holds an encoded NUL (%00)");
    path += static_cast<char>(high * 16 + low);
    i += 2;
  }
  return std::filesystem::path(path);
}

std::string file_uri(const std::filesystem::path& path) {
  const std::string text = std::filesystem::absolute(path).lexically_normal().string();
  std::string uri = "file://";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || std::string_view("-._~!$&'()*+,;=:@/").find(c) != std::string_view::npos) {
      uri += c;
    } else {
      char escape[4];
      std::snprintf(escape, sizeof escape, "%%%02X", u);
      uri += escape;
    }
  }
  return uri;
}

RenderJob thumbnail_render_job(const std::filesystem::path& model, int size, int threads) {
  check_size(size);
  RenderJob job;
  job.model = model;
  job.width = job.height = size;
  job.look.transparent_background = true;
  job.camera.fill = true;
  job.samples = 4;
  job.load.threads = threads;
  return job;
}

Thumbnail draw_thumbnail(const ThumbnailJob& job, Renderer& renderer) {
  check_size(job.size);
  const std::filesystem::path model = path_of_uri(job.input);
  const std::string source = model.string();
  // stat() once: the size and time written are those of the file read, and a FIFO is refused before it is opened.
  struct stat status {};
  if (::stat(source.c_str(), &status) != 0) throw InputError(source, errno_text(errno));
  if (!S_ISREG(status.st_mode)) throw InputError(source, "not a regular file");
  const auto bytes = static_cast<std::uintmax_t>(status.st_size);
  if (bytes > job.max_input_bytes)
    throw InputError(source, "the file is " + std::to_string(bytes) + " bytes, over the thumbnail limit of " +
                                 std::to_string(job.max_input_bytes));
  const RenderJob render = thumbnail_render_job(model, job.size, job.threads);
  Thumbnail out;
  out.size = job.size;
  out.rgba = render_buffers(render, renderer, BufferRequest{}).color;
  const std::string uri = starts_with_nocase(job.input, "file:") ? job.input : file_uri(model);
  out.text = {{"Thumb::URI", uri},
              {"Thumb::MTime", std::to_string(static_cast<long long>(status.st_mtime))},
              {"Thumb::Size", std::to_string(bytes)},
              {"Software", std::string("facet ") + kVersion}};
  return out;
}

void write_thumbnail(const Thumbnail& thumbnail, const std::filesystem::path& output) {
  write_png(output, thumbnail.size, thumbnail.size, thumbnail.rgba, true, 1, thumbnail.text);
}

void render_thumbnail(const ThumbnailJob& job, Renderer& renderer) {
  write_thumbnail(draw_thumbnail(job, renderer), job.output);
}

std::span<const ModelMimeType> thumbnail_mime_types() { return kTypes; }

}  // namespace facet
