// image_io.hpp - writing rendered images (PNG) and float and id buffers (NumPy .npy, OpenEXR); reading PNGs back.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace facet {

class Framebuffer;

// A PNG text chunk (tEXt): a keyword of 1 to 79 printable Latin-1 characters and its text, without NUL bytes. The
// freedesktop thumbnail specification's Thumb::URI and Thumb::MTime are ones.
struct PngText {
  std::string keyword;
  std::string text;
};

// Writes an 8-bit PNG from rgba (R, G, B, A bytes per pixel, top row first); RGB only when keep_alpha is false.
// A regular file (or the one a symlink points to) is written under a temporary name in the same folder and renamed
// into place, so a failure never leaves a partial file at path. "-" is standard output; a device, a FIFO or a link
// into /proc/self/fd (such as /dev/stdout) is opened and written in place, never replaced. Throws std::invalid_argument
// for a bad size or text chunk, std::runtime_error("<path>: <reason>") when the file cannot be written. Up to
// `threads` threads (the caller's included) compress bands of rows at once; a frame of 1920x1080 takes two bands
// or more. `text` chunks are written before the pixels.
void write_png(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> rgba,
               bool keep_alpha = true, int threads = 1, std::span<const PngText> text = {});
void write_png(const std::filesystem::path& path, const Framebuffer& framebuffer, bool keep_alpha = true,
               int threads = 1);

// An 8-bit greyscale PNG of width * height values, top row first; written like write_png.
void write_png_gray(const std::filesystem::path& path, int width, int height, std::span<const std::uint8_t> gray);

// A text file, written like write_png (a temporary file renamed into place).
void write_text(const std::filesystem::path& path, const std::string& text);

// An animated GIF of `frames` (each width * height RGBA bytes, top row first; alpha ignored), looping forever, each
// frame shown delay_centiseconds, with one 256-colour palette chosen over all frames. Written like write_png.
void write_gif(const std::filesystem::path& path, int width, int height,
               std::span<const std::vector<std::uint8_t>> frames, int delay_centiseconds);

// True when path names an animation container facet writes: .gif, .mp4 or .webm, in any case.
bool is_animation_path(const std::filesystem::path& path);

// An animation of `frames` (as write_gif's), frame_seconds apart, in the container the path's extension names: an
// animated GIF (frame times rounded to whole centiseconds, at least 2), H.264 in MP4 or VP9 in WebM (4:2:0, so an
// odd width or height gains a repeated edge column or row). Written like write_png. Throws std::invalid_argument
// for another extension.
void write_animation(const std::filesystem::path& path, int width, int height,
                     std::span<const std::vector<std::uint8_t>> frames, double frame_seconds);

// Reads a PNG (or any format load_texture accepts) as RGBA bytes, top row first. Throws InputError naming the file.
std::vector<std::uint8_t> read_png(const std::filesystem::path& path, int& width, int& height);

// Writes values (width*height floats, top row first) as a NumPy .npy file: version 1.0, dtype '<f4', shape
// (height, width), C order, data starting at byte 64 * k. Written atomically and with the errors of write_png.
void write_npy(const std::filesystem::path& path, int width, int height, std::span<const float> values);
// The same for uint32 values ('<u4'), pixel by pixel with `channels` values each: shape (height, width, channels),
// or (height, width) for one channel.
void write_npy(const std::filesystem::path& path, int width, int height, int channels,
               std::span<const std::uint32_t> values);

// Float values, pixel by pixel with `channels` values each, top row first: as .npy of shape (height, width) or
// (height, width, channels), or, when the path ends in .exr (any case), as OpenEXR with 32-bit float channels and
// ZIP compression (1 channel: Y; 2: R G; 3: R G B; other counts are refused with std::invalid_argument). Written
// like write_png.
void write_float_image(const std::filesystem::path& path, int width, int height, int channels,
                       std::span<const float> values);

}  // namespace facet
