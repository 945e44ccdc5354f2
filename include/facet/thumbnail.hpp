// thumbnail.hpp - thumbnails for file managers: the freedesktop thumbnailer's render and the model types it covers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facet/image_io.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"

namespace facet {

// The freedesktop thumbnail sizes run from 128 (normal) to 1024 pixels (xx-large); a file manager asks for one.
inline constexpr int kDefaultThumbnailSize = 256;
inline constexpr int kMaxThumbnailSize = 2048;
// A thumbnailer stops after this long (seconds), so that a file manager never waits on one file,
inline constexpr double kDefaultThumbnailSeconds = 5.0;
// and refuses model files larger than this (256 MiB): a thumbnail of more is never worth its memory.
inline constexpr std::uintmax_t kDefaultThumbnailInputBytes = std::uintmax_t{256} << 20;

// One thumbnail, as a file manager asks for it (`facet thumbnail -s SIZE INPUT OUTPUT`).
struct ThumbnailJob {
  std::string input;             // the model: a path, or a file:// URI (percent-encoded, RFC 8089)
  std::filesystem::path output;  // the PNG written
  int size = kDefaultThumbnailSize;
  std::uintmax_t max_input_bytes = kDefaultThumbnailInputBytes;
  int threads = 0;  // render threads; 0: one per core
};

// The local path that `input` names: a file:// URI's path (file:///p, file://localhost/p or file:/p),
// percent-decoded; anything without a scheme is a path already. Throws InputError(input, ...) for another scheme
// or host (the thumbnailer reads local files only), a bad percent escape, or an encoded NUL.
std::filesystem::path path_of_uri(std::string_view input);

// The file:// URI of a path (made absolute), with every byte outside RFC 3986's unreserved characters, the
// sub-delimiters, ':', '@' and '/' percent-encoded, as GLib's g_filename_to_uri writes it.
std::string file_uri(const std::filesystem::path& path);

// The render a thumbnail of `model` is: size x size pixels, the model's own look on a transparent background,
// 4 samples a pixel, the model filling the square (CameraSpec::fill).
RenderJob thumbnail_render_job(const std::filesystem::path& model, int size, int threads = 0);

// A drawn thumbnail: size x size RGBA pixels, top row first, and the freedesktop metadata its PNG carries.
struct Thumbnail {
  int size = 0;
  std::vector<std::uint8_t> rgba;
  std::vector<PngText> text;
};

// Draws the thumbnail. Its metadata: Thumb::URI (the input's URI as given, or the path's), Thumb::MTime (the
// model's modification time, seconds since 1970), Thumb::Size (its bytes) and Software. Throws
// std::invalid_argument for a size outside 1..kMaxThumbnailSize, InputError for a model that is missing, not a
// regular file, larger than max_input_bytes or unreadable, and as render() does.
Thumbnail draw_thumbnail(const ThumbnailJob& job, Renderer& renderer);

// Writes it as an RGBA PNG with its metadata, as write_png writes (never a partial file at `output`).
void write_thumbnail(const Thumbnail& thumbnail, const std::filesystem::path& output);

// draw_thumbnail, then write_thumbnail to job.output.
void render_thumbnail(const ThumbnailJob& job, Renderer& renderer);

// A MIME type of model files facet reads, and the file name pattern that marks it.
struct ModelMimeType {
  std::string_view type;
  std::string_view glob;
  // Defined by facet's shared-mime-info package (data/facet-mime.xml) rather than by Debian's freedesktop.org
  // database, which lacks it.
  bool facet_defines = false;
};

// Every MIME type facet's thumbnailer entry lists (data/facet.thumbnailer.in).
std::span<const ModelMimeType> thumbnail_mime_types();

}  // namespace facet
