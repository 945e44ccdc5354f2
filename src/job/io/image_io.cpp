// image_io.cpp - PNG (zlib), GIF, .npy and OpenEXR writers over write_output, and a PNG reader for tests.
#include "facet/image_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "facet/detail/bits.hpp"
#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "job/io/exr.hpp"
#include "core/file_util.hpp"
#include "job/io/gif.hpp"
#include "job/io/output_file.hpp"
#include "job/io/png.hpp"
#include "job/io/video.hpp"
#include "scene/texture/image_decode.hpp"


namespace facet {

namespace {

void check_size(int width, int height, std::size_t count, std::size_t per_pixel, const char* what) {
  if (width < 1 || height < 1 || width > kMaxDimension || height > kMaxDimension)
    throw std::invalid_argument(std::string(what) + " size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1.." + std::to_string(kMaxDimension));
  if (count != static_cast<std::size_t>(width) * height * per_pixel)
    throw std::invalid_argument(std::string(what) + " of " + std::to_string(width) + "x" + std::to_string(height) +
                                " given " + std::to_string(count) + " values");
}

}  // namespace

void write_png(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgba,
               bool keep_alpha, int threads, std::span<const PngText> text) {
  check_size(width, height, rgba.size(), 4, "PNG");
  write_output(path, encode_png(width, height, keep_alpha ? 4 : 3, rgba, 4, threads, text));
}

void write_png_gray(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> gray) {
  check_size(width, height, gray.size(), 1, "PNG");
  write_output(path, encode_png(width, height, 1, gray));
}

void write_gif(const std::filesystem::path& path, int width, int height,
               std::span<const std::vector<std::uint8_t>> frames, int delay_centiseconds) {
  for (const std::vector<std::uint8_t>& frame : frames) check_size(width, height, frame.size(), 4, "GIF");
  write_output(path, encode_gif(width, height, frames, delay_centiseconds));
}

bool is_animation_path(const std::filesystem::path& path) {
  const std::string extension = lower_extension(path);
  return extension == ".gif" || extension == ".mp4" || extension == ".webm";
}

void write_animation(const std::filesystem::path& path, int width, int height,
                     std::span<const std::vector<std::uint8_t>> frames, double frame_seconds) {
  const std::string extension = lower_extension(path);
  if (extension == ".gif")
    return write_gif(path, width, height, frames, std::max(2, static_cast<int>(std::lround(frame_seconds * 100.0))));
  if (extension != ".mp4" && extension != ".webm")
    throw std::invalid_argument(path.string() + ": facet writes animations as .gif, .mp4 or .webm");
  for (const std::vector<std::uint8_t>& frame : frames) check_size(width, height, frame.size(), 4, "video");
  const VideoFormat format = extension == ".mp4" ? VideoFormat::mp4 : VideoFormat::webm;
  write_output(path, encode_video(format, width, height, frames, frame_seconds));
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_output(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

void write_png(const std::filesystem::path& path, const Framebuffer& framebuffer, bool keep_alpha, int threads) {
  if constexpr (detail::kLittleEndian) {
    // Packed pixels are R, G, B, A in memory on a little-endian machine: encoded where they lie, without a copy.
    const std::span<const std::uint32_t> color = framebuffer.color();
    write_png(path, framebuffer.width(), framebuffer.height(),
              std::span(reinterpret_cast<const std::uint8_t*>(color.data()), color.size_bytes()), keep_alpha, threads);
  } else {
    write_png(path, framebuffer.width(), framebuffer.height(), framebuffer.rgba8(), keep_alpha, threads);
  }
}

std::vector<std::uint8_t> read_png(const std::filesystem::path& path, int& width, int& height) {
  DecodedImage image = decode_image(read_image_file(path), kMaxDimension, path.string());
  width = image.width;
  height = image.height;
  return std::move(image.rgba);
}

namespace {

// NumPy .npy, version 1.0, C order, little-endian 4-byte elements; shape (height, width) or (height, width, channels).
template <class T>
void write_npy_words(const std::filesystem::path& path, const char* descr, int width, int height, int channels,
                     std::span<const T> values) {
  static_assert(sizeof(T) == 4);
  if (channels < 1) throw std::invalid_argument("npy array: channel count " + std::to_string(channels));
  check_size(width, height, values.size(), static_cast<std::size_t>(channels), "npy array");
  std::string header = std::string("{'descr': '") + descr + "', 'fortran_order': False, 'shape': (" +
                       std::to_string(height) + ", " + std::to_string(width);
  if (channels > 1) header += ", " + std::to_string(channels);
  header += "), }";
  // 10 bytes of magic, version and length precede the header; pad with spaces so the data starts at a multiple of
  // 64 bytes (what NumPy itself writes), ending the header with a newline.
  header.append(63 - (10 + header.size()) % 64, ' ');
  header += '\n';
  std::vector<std::uint8_t> bytes(10 + header.size() + values.size() * 4);
  const char magic[] = "\x93NUMPY\x01\x00";
  std::memcpy(bytes.data(), magic, 8);
  bytes[8] = static_cast<std::uint8_t>(header.size() & 0xff);
  bytes[9] = static_cast<std::uint8_t>(header.size() >> 8);
  std::memcpy(bytes.data() + 10, header.data(), header.size());
  std::uint8_t* out = bytes.data() + 10 + header.size();
  for (const T v : values) {
    const auto bits = detail::bit_cast<std::uint32_t>(v);
    for (int b = 0; b < 4; ++b) *out++ = static_cast<std::uint8_t>(bits >> (8 * b));  // little-endian
  }
  write_output(path, bytes);
}

bool is_exr(const std::filesystem::path& path) { return lower_extension(path) == ".exr"; }

}  // namespace

void write_npy(const std::filesystem::path& path, int width, int height, std::span<const float> values) {
  write_npy_words(path, "<f4", width, height, 1, values);
}

void write_npy(const std::filesystem::path& path, int width, int height, int channels,
               std::span<const std::uint32_t> values) {
  write_npy_words(path, "<u4", width, height, channels, values);
}

void write_float_image(const std::filesystem::path& path, int width, int height, int channels,
                       std::span<const float> values) {
  if (!is_exr(path)) return write_npy_words(path, "<f4", width, height, channels, values);
  if (channels < 1) throw std::invalid_argument("EXR image: channel count " + std::to_string(channels));
  check_size(width, height, values.size(), static_cast<std::size_t>(channels), "EXR image");
  write_output(path, encode_exr(width, height, channels, values));
}

}  // namespace facet
