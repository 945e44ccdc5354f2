// png.cpp - the PNG encoder: signature, IHDR, one IDAT of Up-filtered rows compressed by libdeflate, IEND.
#include "job/io/png.hpp"

#include <libdeflate.h>

#include "facet/framebuffer.hpp"

#include <array>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

namespace facet {
namespace {

constexpr int kLevel = 2;

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// One compressor per thread, kept: allocating one costs more than compressing a small image.
libdeflate_compressor* compressor() {
  thread_local std::unique_ptr<libdeflate_compressor, CompressorDeleter> kept(libdeflate_alloc_compressor(kLevel));
  if (!kept) throw std::runtime_error("PNG: libdeflate could not allocate a compressor");
  return kept.get();
}

void store_u32(std::uint8_t* out, std::uint32_t v) {  // PNG integers are big-endian
  out[0] = static_cast<std::uint8_t>(v >> 24);
  out[1] = static_cast<std::uint8_t>(v >> 16);
  out[2] = static_cast<std::uint8_t>(v >> 8);
  out[3] = static_cast<std::uint8_t>(v);
}

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.resize(out.size() + 4);
  store_u32(out.data() + out.size() - 4, v);
}

// A chunk: length, type, data, and the CRC of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char* type, std::span<const std::uint8_t> data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.resize(start + 4 + data.size());
  std::memcpy(out.data() + start, type, 4);
  if (!data.empty()) std::memcpy(out.data() + start + 4, data.data(), data.size());
  put_u32(out, libdeflate_crc32(0, out.data() + start, out.size() - start));
}

}  // namespace

std::vector<std::uint8_t> encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels,
                                     int source_channels) {
  if (source_channels == 0) source_channels = channels;
  if (width < 1 || height < 1 || (channels != 1 && channels != 3 && channels != 4) || source_channels < channels ||
      source_channels > 4)
    throw std::invalid_argument("PNG: bad size " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                                std::to_string(channels));
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  const std::size_t source_row = static_cast<std::size_t>(width) * static_cast<std::size_t>(source_channels);
  if (pixels.size() != source_row * static_cast<std::size_t>(height))
    throw std::invalid_argument("PNG: " + std::to_string(pixels.size()) + " bytes for " + std::to_string(width) + "x" +
                                std::to_string(height) + "x" + std::to_string(channels));

  // Filter type 2 (Up) on every row; the first row's "row above" is zero, so it is stored as it is.
  // Both work buffers are as large as the image: on huge pages, they fault in 2 MiB at a time (framebuffer.hpp).
  std::vector<std::uint8_t, CacheAlignedAllocator<std::uint8_t>> filtered((row + 1) * static_cast<std::size_t>(height));
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    std::uint8_t* out = filtered.data() + y * (row + 1);
    const std::uint8_t* line = pixels.data() + y * source_row;
    out[0] = 2;
    if (source_channels == channels) {
      if (y == 0) {
        std::memcpy(out + 1, line, row);
      } else {
        const std::uint8_t* above = line - source_row;
        for (std::size_t i = 0; i < row; ++i) out[1 + i] = static_cast<std::uint8_t>(line[i] - above[i]);
      }
      continue;
    }
    const std::uint8_t* above = y == 0 ? nullptr : line - source_row;
    const auto n = static_cast<std::size_t>(channels), m = static_cast<std::size_t>(source_channels);
    for (std::size_t x = 0; x < static_cast<std::size_t>(width); ++x)
      for (std::size_t c = 0; c < n; ++c)
        out[1 + x * n + c] = static_cast<std::uint8_t>(line[x * m + c] - (above ? above[x * m + c] : 0));
  }
  libdeflate_compressor* c = compressor();
  std::vector<std::uint8_t, CacheAlignedAllocator<std::uint8_t>> zlib(
      libdeflate_zlib_compress_bound(c, filtered.size()));
  const std::size_t compressed =
      libdeflate_zlib_compress(c, filtered.data(), filtered.size(), zlib.data(), zlib.size());
  if (compressed == 0) throw std::runtime_error("PNG: compression failed");

  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  png.reserve(compressed + 64);
  // Size, then bit depth 8, the colour type (grey, RGB, RGBA), deflate, adaptive filtering, no interlacing.
  std::array<std::uint8_t, 13> header{0, 0, 0, 0, 0, 0, 0, 0, 8, 0, 0, 0, 0};
  store_u32(header.data(), static_cast<std::uint32_t>(width));
  store_u32(header.data() + 4, static_cast<std::uint32_t>(height));
  header[9] = channels == 1 ? 0 : channels == 3 ? 2 : 6;
  put_chunk(png, "IHDR", header);
  put_chunk(png, "IDAT", std::span(zlib.data(), compressed));
  put_chunk(png, "IEND", {});
  return png;
}

}  // namespace facet
