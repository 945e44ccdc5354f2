// exr.cpp - OpenEXR encoding and decoding through OpenEXR's C core library, in memory: the caller writes the
// encoded bytes atomically, and reads a whole file before decoding it.
#include "job/io/exr.hpp"

#include <openexr.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

#include "facet/error.hpp"

namespace facet {
namespace {

// OpenEXR's C core rather than its C++ library: the C++ one (with Imath, Iex and IlmThread) was mapped, relocated
// and constructed in every facet process, 2 ms of its start; the core is one small C library.

// Where the core writes: at the offsets it asks for, growing the bytes as needed (the chunk offset table is written
// last, back after the header). Its messages are kept for the exception rather than printed on stderr.
struct Output {
  std::vector<std::uint8_t>& bytes;
  std::string message;
};

// The output of the encoding under way on this thread, for the error handler: the core may report an error while
// it holds the context's lock, so the handler cannot ask the context for its user data.
thread_local Output* current_output = nullptr;

// Called from C, so no exception leaves it: running out of memory is reported as a failed write.
int64_t write_at(exr_const_context_t, void* user, const void* buffer, uint64_t size, uint64_t offset,
                 exr_stream_error_func_ptr_t) noexcept {
  try {
    std::vector<std::uint8_t>& bytes = static_cast<Output*>(user)->bytes;
    const std::size_t end = static_cast<std::size_t>(offset + size);
    if (end > bytes.size()) bytes.resize(end);
    std::memcpy(bytes.data() + offset, buffer, static_cast<std::size_t>(size));
    return static_cast<int64_t>(size);
  } catch (...) {
    return -1;
  }
}

// Keeps the first message; one that cannot be copied (no memory) leaves the generic message for the code.
void keep_message(exr_const_context_t, exr_result_t, const char* message) noexcept {
  Output* output = current_output;
  if (!output || !output->message.empty() || !message) return;
  try {
    output->message = message;
  } catch (...) {
    output->message.clear();
  }
}

// Throws for a failed call with the first message the core gave, or the generic one for its code.
void check(exr_result_t result, const Output& output) {
  if (result == EXR_ERR_SUCCESS) return;
  const std::string message = output.message.empty() ? exr_get_default_error_message(result) : output.message;
  throw std::runtime_error("OpenEXR: " + message);
}

}  // namespace

std::vector<std::uint8_t> encode_exr(int width, int height, int channels, std::span<const float> values) {
  if (channels < 1 || channels > 3)
    throw std::invalid_argument("EXR: 1, 2 or 3 channels, not " + std::to_string(channels));
  std::vector<std::uint8_t> bytes;
  Output output{bytes, {}};
  current_output = &output;
  struct Forget {
    ~Forget() { current_output = nullptr; }
  } forget;
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.user_data = &output;
  init.write_fn = write_at;
  init.error_handler_fn = keep_message;
  exr_context_t context = nullptr;
  check(exr_start_write(&context, "memory", EXR_WRITE_FILE_DIRECTLY, &init), output);
  exr_encode_pipeline_t encoder{};
  bool encoding = false;
  try {
    int part = 0;
    check(exr_add_part(context, nullptr, EXR_STORAGE_SCANLINE, &part), output);
    check(exr_initialize_required_attr_simple(context, part, width, height, EXR_COMPRESSION_ZIP), output);
    // Not perceptually linear, as OpenEXR's C++ library marks a channel by default.
    // One channel is grey (Y), two a vector (R G: motion's x and y), three a colour or normal (R G B).
    const char* const names = channels == 1 ? "Y" : channels == 2 ? "RG" : "RGB";
    for (int c = 0; c < channels; ++c) {
      const char name[2] = {names[c], '\0'};
      check(exr_add_channel(context, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1), output);
    }
    check(exr_write_header(context), output);

    int lines = 0;
    check(exr_get_scanlines_per_chunk(context, part, &lines), output);
    const std::size_t pixel_bytes = sizeof(float) * static_cast<std::size_t>(channels);
    const std::size_t row_bytes = pixel_bytes * static_cast<std::size_t>(width);
    for (int y = 0; y < height; y += lines) {
      exr_chunk_info_t chunk{};
      check(exr_write_scanline_chunk_info(context, part, y, &chunk), output);
      const bool first = !encoding;
      if (first) {
        check(exr_encoding_initialize(context, part, &chunk, &encoder), output);
        encoding = true;
      } else {
        check(exr_encoding_update(context, part, &chunk, &encoder), output);
      }
      // The core lists the channels sorted by name (B G R); each reads its own float of every pixel.
      for (int k = 0; k < encoder.channel_count; ++k) {
        exr_coding_channel_info_t& channel = encoder.channels[k];
        const std::size_t c = std::string_view(names).find(channel.channel_name[0]);
        channel.encode_from_ptr = reinterpret_cast<const std::uint8_t*>(values.data() + c) +
                                  row_bytes * static_cast<std::size_t>(chunk.start_y);
        channel.user_pixel_stride = static_cast<int32_t>(pixel_bytes);
        channel.user_line_stride = static_cast<int32_t>(row_bytes);
        channel.user_data_type = EXR_PIXEL_FLOAT;
        channel.user_bytes_per_element = sizeof(float);
      }
      // The core picks its packing routine from the layout just described.
      if (first) check(exr_encoding_choose_default_routines(context, part, &encoder), output);
      check(exr_encoding_run(context, part, &encoder), output);
    }
    if (encoding) exr_encoding_destroy(context, &encoder);
    encoding = false;
    check(exr_finish(&context), output);
  } catch (...) {
    if (encoding) exr_encoding_destroy(context, &encoder);
    if (context) exr_finish(&context);
    throw;
  }
  return bytes;
}

namespace {

// Decoding. The core reads the file through read_at and decodes each chunk (a block of scanlines or a tile)
// straight into the RGB output: every channel kept is converted to float and written at its place in the
// interleaved pixels (pixel stride 12 bytes, line stride a row's), the others are skipped.

// The file's bytes, for the core's reads.
struct Input {
  const std::uint8_t* data;
  std::size_t size;
};

// Like pread: as much of the request as the file holds; the core takes a short read for a truncated file.
int64_t read_at(exr_const_context_t, void* user, void* buffer, uint64_t size, uint64_t offset,
                exr_stream_error_func_ptr_t) noexcept {
  const Input& input = *static_cast<const Input*>(user);
  if (offset >= input.size) return 0;
  const std::size_t count = static_cast<std::size_t>(std::min<uint64_t>(size, input.size - offset));
  if (count > 0) std::memcpy(buffer, input.data + offset, count);
  return static_cast<int64_t>(count);
}

// The file's size, against which the core checks the offsets and sizes the header and chunk table claim.
int64_t input_size(exr_const_context_t, void* user) noexcept {
  return static_cast<int64_t>(static_cast<const Input*>(user)->size);
}

// The message of the read under way on this thread (see current_output).
thread_local std::string* current_message = nullptr;

void keep_read_message(exr_const_context_t, exr_result_t, const char* message) noexcept {
  std::string* kept = current_message;
  if (!kept || !kept->empty() || !message) return;
  try {
    *kept = message;
  } catch (...) {
    kept->clear();
  }
}

// Text from the file (a channel name) or the core, fit for a one-line message.
std::string printable(std::string_view text) {
  std::string out(text.substr(0, 200));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

// One read of a file held in memory: the context, the decoding pipeline and the core's messages, all released on
// every path. Neither copied nor moved: the pipeline's channel list may point into the pipeline itself.
class Reading {
 public:
  Reading(const void* data, std::size_t size, const std::string& source)
      : input_{static_cast<const std::uint8_t*>(data), size}, source_(source), previous_(current_message) {
    current_message = &message_;
  }
  ~Reading() {
    if (decoding_) exr_decoding_destroy(context_, &decoder_);
    if (context_) exr_finish(&context_);
    current_message = previous_;
  }
  Reading(const Reading&) = delete;
  Reading& operator=(const Reading&) = delete;

  void start() {
    if (!input_.data && input_.size > 0) fail("no data");
    if (input_.size > static_cast<std::uint64_t>(INT64_MAX)) fail("OpenEXR: file too large");
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &input_;
    init.read_fn = read_at;
    init.size_fn = input_size;
    init.error_handler_fn = keep_read_message;
    // A truncated or damaged file fails rather than having the core search it for chunks its table lost.
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    check(exr_start_read(&context_, source_.empty() ? "memory" : source_.c_str(), &init));
  }

  // Throws for a failed call with the first message the core gave during it, or the generic one for its code.
  void check(exr_result_t result) {
    if (result == EXR_ERR_SUCCESS) {
      message_.clear();
      return;
    }
    fail("OpenEXR: " + printable(message_.empty() ? exr_get_default_error_message(result) : message_));
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(source_, problem); }

  exr_context_t context() const { return context_; }
  bool decoding() const { return decoding_; }

  // The pipeline, initialised for the first chunk, then updated for each of the others.
  exr_decode_pipeline_t& start_decoding(const exr_chunk_info_t& chunk) {
    if (decoding_) {
      check(exr_decoding_update(context_, 0, &chunk, &decoder_));
    } else {
      decoding_ = true;  // exr_decoding_destroy frees what a failed initialisation left
      check(exr_decoding_initialize(context_, 0, &chunk, &decoder_));
    }
    return decoder_;
  }

 private:
  Input input_;
  const std::string& source_;
  std::string message_;
  std::string* previous_;
  exr_context_t context_ = nullptr;
  exr_decode_pipeline_t decoder_{};
  bool decoding_ = false;
};

// Whether a channel named `name` is the colour `c` of some layer: "R", or "diffuse.R".
bool is_channel(std::string_view name, char c) {
  return !name.empty() && name.back() == c && (name.size() == 1 || name[name.size() - 2] == '.');
}

std::string window_text(const exr_attr_box2i_t& window) {
  std::string text = "(";  // appended rather than "(" + ..., which trips GCC 12's -Wrestrict
  text += std::to_string(window.min.x) + ", " + std::to_string(window.min.y) + ") - (";
  text += std::to_string(window.max.x) + ", " + std::to_string(window.max.y) + ")";
  return text;
}

}  // namespace

std::vector<float> decode_exr_rgb(const void* data, std::size_t size, const std::string& source,
                                  const std::function<void(int, int)>& check_size, int& width, int& height) {
  constexpr int part = 0;
  constexpr std::int32_t pixel_bytes = 3 * sizeof(float);
  Reading exr(data, size, source);
  exr.start();
  const exr_context_t context = exr.context();

  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  exr.check(exr_get_storage(context, part, &storage));
  if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED)
    exr.fail("OpenEXR image holds deep data (several samples a pixel), which facet does not read");

  // The data window, whose size the output takes; a line of it must fit the core's 32-bit line stride.
  exr_attr_box2i_t window{};
  exr.check(exr_get_data_window(context, part, &window));
  const std::int64_t w = std::int64_t{window.max.x} - window.min.x + 1;
  const std::int64_t h = std::int64_t{window.max.y} - window.min.y + 1;
  if (w < 1 || h < 1 || w > INT32_MAX / pixel_bytes || h > INT32_MAX)
    exr.fail("OpenEXR data window " + window_text(window) + " is empty or too large");
  check_size(static_cast<int>(w), static_cast<int>(h));
  const std::uint64_t texels = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);

  // R, G and B by name, else Y as grey; every other channel is skipped. The list is sorted by name, as the
  // pipeline's channels are.
  const exr_attr_chlist_t* list = nullptr;
  exr.check(exr_get_channels(context, part, &list));
  const int count = list ? list->num_channels : 0;
  std::array<int, 4> found{-1, -1, -1, -1};  // R, G, B, Y
  std::uint64_t all_channel_bytes = 0;       // per pixel, of every channel
  for (int c = 0; c < count; ++c) {
    const exr_attr_chlist_entry_t& entry = list->entries[c];
    const std::string_view name =
        entry.name.str ? std::string_view(entry.name.str, static_cast<std::size_t>(std::max(entry.name.length, 0)))
                       : std::string_view();
    for (int k = 0; k < 4; ++k)
      if (found[k] < 0 && is_channel(name, "RGBY"[k])) found[k] = c;
    all_channel_bytes += entry.pixel_type == EXR_PIXEL_HALF ? 2 : 4;
  }
  const bool grey = found[0] < 0 && found[1] < 0 && found[2] < 0 && found[3] >= 0;
  std::vector<int> slot(static_cast<std::size_t>(count), -1);  // each channel's float in the output pixel, or -1
  int kept = 0;
  for (int k = 0; k < 3; ++k) {
    const int c = grey ? (k == 0 ? found[3] : -1) : found[k];
    if (c < 0) continue;
    const exr_attr_chlist_entry_t& entry = list->entries[c];
    if (entry.x_sampling != 1 || entry.y_sampling != 1)
      exr.fail("OpenEXR channel '" + printable(entry.name.str ? entry.name.str : "") + "' is subsampled (" +
               std::to_string(entry.x_sampling) + " by " + std::to_string(entry.y_sampling) +
               "), which facet does not read");
    slot[static_cast<std::size_t>(c)] = k;
    ++kept;
  }
  // The core decodes a chunk of every channel at once, skipped ones included: a header listing thousands of
  // channels over a window the file could hold in RGB would have it allocate gigabytes a chunk. So the data of all
  // channels is bounded as the texels are (kMaxExrTexelsPerByte), at up to four floats (16 bytes) a texel.
  constexpr std::uint64_t max_bytes_per_byte = kMaxExrTexelsPerByte * 16;
  const std::uint64_t max_bytes = size > UINT64_MAX / max_bytes_per_byte ? UINT64_MAX : size * max_bytes_per_byte;
  if (all_channel_bytes > 0 && texels > max_bytes / all_channel_bytes)
    exr.fail("OpenEXR image claims " + std::to_string(w) + "x" + std::to_string(h) + " pixels of " +
             std::to_string(count) + " channels, more than its " + std::to_string(size) + " bytes can hold");

  std::vector<float> rgb;
  if (texels > rgb.max_size() / 3) exr.fail("OpenEXR data window " + window_text(window) + " is too large");
  rgb.assign(static_cast<std::size_t>(texels) * 3, 0.0f);

  exr_compression_t compression = EXR_COMPRESSION_NONE;
  exr.check(exr_get_compression(context, part, &compression));
  // OpenEXR 3.1's half-to-float routines for three- and four-channel parts assume every channel is decoded (they
  // write through a skipped channel's null pointer); in such a part the skipped channels are decoded into a
  // throw-away buffer of one chunk's size instead, which also keeps the core on its general routine.
  const bool scratch_others = (count == 3 || count == 4) && kept < count;
  std::vector<float> scratch;
  // A chunk that compression would not have made smaller is stored as it is (packed size = unpacked size). OpenEXR
  // before 3.3 decompresses such a B44 or B44A chunk all the same, scrambling its pixels (a part of float or uint
  // channels, which B44 leaves as they are, is always stored so): those chunks skip decompression.
  const bool b44 = compression == EXR_COMPRESSION_B44 || compression == EXR_COMPRESSION_B44A;
  decltype(exr_decode_pipeline_t::decompress_fn) decompress = nullptr;

  // Decodes one chunk whose top left pixel is (x0, y0) in the data window.
  const auto decode_chunk = [&](const exr_chunk_info_t& chunk, std::int64_t x0, std::int64_t y0) {
    if (chunk.width < 1 || chunk.height < 1 || x0 < 0 || y0 < 0 || x0 + chunk.width > w || y0 + chunk.height > h)
      exr.fail("OpenEXR chunk " + std::to_string(chunk.idx) + " (" + std::to_string(chunk.width) + "x" +
               std::to_string(chunk.height) + " pixels at " + std::to_string(x0) + ", " + std::to_string(y0) +
               ") lies outside the data window " + window_text(window));
    if (compression == EXR_COMPRESSION_NONE && chunk.packed_size != chunk.unpacked_size)
      exr.fail("OpenEXR chunk " + std::to_string(chunk.idx) + " holds " + std::to_string(chunk.packed_size) +
               " bytes, not the " + std::to_string(chunk.unpacked_size) + " its pixels take");
    const bool first = !exr.decoding();
    exr_decode_pipeline_t& decoder = exr.start_decoding(chunk);
    if (decoder.channel_count != count) exr.fail("OpenEXR: channel list changed while decoding");
    const std::size_t chunk_texels = static_cast<std::size_t>(chunk.width) * static_cast<std::size_t>(chunk.height);
    if (scratch_others && scratch.size() < chunk_texels) scratch.resize(chunk_texels);
    float* const origin =
        rgb.data() + (static_cast<std::size_t>(y0) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x0)) * 3;
    for (int c = 0; c < decoder.channel_count; ++c) {
      exr_coding_channel_info_t& channel = decoder.channels[c];
      const int k = slot[static_cast<std::size_t>(c)];
      if (k >= 0) {
        if (channel.width != chunk.width || channel.height != chunk.height)
          exr.fail("OpenEXR channel '" + printable(channel.channel_name ? channel.channel_name : "") +
                   "' does not cover its chunk");
        channel.decode_to_ptr = reinterpret_cast<std::uint8_t*>(origin + k);
        channel.user_pixel_stride = pixel_bytes;
        channel.user_line_stride = static_cast<int32_t>(w) * pixel_bytes;
      } else if (scratch_others) {
        channel.decode_to_ptr = reinterpret_cast<std::uint8_t*>(scratch.data());
        channel.user_pixel_stride = sizeof(float);
        channel.user_line_stride = chunk.width * static_cast<int32_t>(sizeof(float));
      } else {
        channel.decode_to_ptr = nullptr;
        continue;
      }
      channel.user_data_type = EXR_PIXEL_FLOAT;
      channel.user_bytes_per_element = sizeof(float);
    }
    // The core picks its routines from the layout just described, which every later chunk keeps.
    if (first) {
      exr.check(exr_decoding_choose_default_routines(context, part, &decoder));
      decompress = decoder.decompress_fn;
    }
    if (b44) decoder.decompress_fn = chunk.packed_size == chunk.unpacked_size ? nullptr : decompress;
    exr.check(exr_decoding_run(context, part, &decoder));
  };

  if (kept > 0) {
    if (storage == EXR_STORAGE_SCANLINE) {
      int32_t lines = 0;
      exr.check(exr_get_scanlines_per_chunk(context, part, &lines));
      if (lines < 1) exr.fail("OpenEXR: invalid scanlines per chunk (" + std::to_string(lines) + ")");
      for (std::int64_t y = window.min.y; y <= window.max.y; y += lines) {
        exr_chunk_info_t chunk{};
        exr.check(exr_read_scanline_chunk_info(context, part, static_cast<int>(y), &chunk));
        if (chunk.start_x != window.min.x || chunk.width != w)
          exr.fail("OpenEXR chunk " + std::to_string(chunk.idx) + " does not span the data window");
        decode_chunk(chunk, 0, std::int64_t{chunk.start_y} - window.min.y);
      }
    } else {
      // The full-resolution level (0, 0) of a tiled image, mipmapped or not: tiles from the window's top left.
      uint32_t tile_width = 0, tile_height = 0;
      exr_tile_level_mode_t level_mode{};
      exr_tile_round_mode_t round_mode{};
      exr.check(exr_get_tile_descriptor(context, part, &tile_width, &tile_height, &level_mode, &round_mode));
      if (tile_width < 1 || tile_height < 1) exr.fail("OpenEXR: invalid tile size");
      const std::int64_t columns = (w + tile_width - 1) / tile_width;
      const std::int64_t rows = (h + tile_height - 1) / tile_height;
      for (std::int64_t ty = 0; ty < rows; ++ty)
        for (std::int64_t tx = 0; tx < columns; ++tx) {
          exr_chunk_info_t chunk{};
          exr.check(exr_read_tile_chunk_info(context, part, static_cast<int>(tx), static_cast<int>(ty), 0, 0, &chunk));
          decode_chunk(chunk, tx * tile_width, ty * tile_height);
        }
    }
  }
  if (grey)
    for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i];
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return rgb;
}

}  // namespace facet
