// exr.cpp - OpenEXR encoding through OpenEXR's C core library, into memory so the caller can write atomically.
#include "io/exr.hpp"

#include <openexr.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>

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
  if (channels != 1 && channels != 3)
    throw std::invalid_argument("EXR: 1 or 3 channels, not " + std::to_string(channels));
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
    const char* const names = channels == 1 ? "Y" : "RGB";
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

}  // namespace facet
