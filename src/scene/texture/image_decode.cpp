// image_decode.cpp - PNG through libspng, JPEG through TurboJPEG, TGA and BMP through stb_image, all bounded.
#include "scene/texture/image_decode.hpp"

// A build without libspng and TurboJPEG (the browser page's, FACET_NO_IMAGE_CODECS) decodes every image with
// stb_image, within the same bounds.
#ifndef FACET_NO_IMAGE_CODECS
#include <spng.h>
#include <turbojpeg.h>
#endif

#include <algorithm>
#include <climits>
#include <memory>

#include "facet/error.hpp"
#include "scene/texture/stb.hpp"

namespace facet {

namespace {

// A decoder's work and memory follow the texels an image's header declares, so a header may declare no more than its
// file's bytes can describe: a 485 KB BMP declaring 9,985 x 8,229 texels would otherwise be decoded into 330 MB of
// zeros. Uncompressed images (BMP, TGA types 1-3) must hold every texel's bytes; a TGA's run-length packets describe
// at most 128 texels in two bytes; deflate expands a byte to at most 1,032 (PNG, by its bits per texel); a baseline
// JPEG spends at least two bits on each 8x8 block it codes (256 texels a byte); a progressive one's end-of-band
// runs skip blocks by the thousand, so it is bounded by deflate's figure for one-bit texels alone (8,256).
constexpr std::uint64_t kDeflateRatio = 1032;
constexpr std::uint64_t kBaselineJpegTexelsPerByte = 256;
constexpr std::uint64_t kRleTexelsPerByte = 64;

void check_size(int width, int height, int max_size, const std::string& source) {
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw InputError(source, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels; the limit is 1.." + std::to_string(max_size) + " per side");
}

std::uint64_t texels(int width, int height) {
  return static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
}

// Refuses an image whose header declares more than its file can hold: `needed` bytes of data where `available`
// are (or, for compressed data, that many texels where the file's bytes can describe only `available`).
void check_backed(std::uint64_t needed, std::uint64_t available, int width, int height, const std::string& what,
                  const std::string& source) {
  if (needed > available)
    throw InputError(source, what + " declares " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels, more than its bytes can hold (needs " + std::to_string(needed) +
                                 ", has " + std::to_string(available) + ")");
}

std::uint32_t u16le(std::span<const unsigned char> b, std::size_t at) { return b[at] | b[at + 1] << 8; }
std::uint32_t u32le(std::span<const unsigned char> b, std::size_t at) {
  return u16le(b, at) | static_cast<std::uint32_t>(u16le(b, at + 2)) << 16;
}

bool is_png(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin());
}

bool is_jpeg(std::span<const unsigned char> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

// The pixel data a BMP or TGA header (already read by stb_image as width x height) promises, against the file.
void check_stb_bounds(std::span<const unsigned char> bytes, int width, int height, const std::string& source) {
  const std::uint64_t size = bytes.size();
  if (size >= 30 && bytes[0] == 'B' && bytes[1] == 'M') {
    const std::uint32_t dib = u32le(bytes, 14);
    const std::uint32_t bits = dib == 12 ? u16le(bytes, 24) : u16le(bytes, 28);
    const std::uint32_t compression = dib == 12 || size < 34 ? 0 : u32le(bytes, 30);
    if (compression != 0 && compression != 3 && compression != 6) return;  // stb_image refuses the rest
    const std::uint64_t stride = (static_cast<std::uint64_t>(width) * bits + 31) / 32 * 4;
    const std::uint64_t offset = std::min<std::uint64_t>(u32le(bytes, 10), size);
    check_backed(stride * static_cast<std::uint64_t>(height), size - offset, width, height, "BMP", source);
    return;
  }
  if (size < 18) return;
  const std::uint64_t type = bytes[2], pixel_bytes = (bytes[16] + 7u) / 8u;
  const std::uint64_t palette = bytes[1] ? u16le(bytes, 5) * ((bytes[7] + 7u) / 8u) : 0;
  const std::uint64_t data = std::min<std::uint64_t>(size, 18 + bytes[0] + palette);
  if (type >= 1 && type <= 3)
    check_backed(texels(width, height) * pixel_bytes, size - data, width, height, "TGA", source);
  else if (type >= 9 && type <= 11)
    check_backed(texels(width, height), (size - data) * kRleTexelsPerByte, width, height, "run-length TGA",
                 source);
}

#ifndef FACET_NO_IMAGE_CODECS
DecodedImage decode_png(std::span<const unsigned char> bytes, int max_size, const std::string& source) {
  std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> png(spng_ctx_new(0), &spng_ctx_free);
  if (!png) throw std::bad_alloc();
  const auto fail = [&](int code) {
    throw InputError(source, std::string("cannot decode PNG (libspng: ") + spng_strerror(code) + ")");
  };
  // Ancillary chunks' checksums are not checked (as browsers and stb do not); critical ones are.
  spng_set_crc_action(png.get(), SPNG_CRC_USE, SPNG_CRC_USE);
  spng_set_image_limits(png.get(), static_cast<std::uint32_t>(max_size), static_cast<std::uint32_t>(max_size));
  spng_set_chunk_limits(png.get(), 1u << 26, 1u << 26);
  if (int e = spng_set_png_buffer(png.get(), bytes.data(), bytes.size())) fail(e);
  spng_ihdr header{};
  if (int e = spng_get_ihdr(png.get(), &header)) {
    if (e == SPNG_EWIDTH || e == SPNG_EHEIGHT || e == SPNG_EUSER_WIDTH || e == SPNG_EUSER_HEIGHT)
      throw InputError(source, "image is wider or taller than " + std::to_string(max_size) + " texels");
    fail(e);
  }
  DecodedImage out;
  out.width = static_cast<int>(header.width);
  out.height = static_cast<int>(header.height);
  check_size(out.width, out.height, max_size, source);
  // Deflate's filtered rows: a filter byte and the row's texels at their bits each.
  const std::uint64_t channels = header.color_type == 2 ? 3 : header.color_type == 4 ? 2 : header.color_type == 6 ? 4 : 1;
  const std::uint64_t row = 1 + (static_cast<std::uint64_t>(out.width) * channels * header.bit_depth + 7) / 8;
  check_backed(row * header.height, kDeflateRatio * bytes.size(), out.width, out.height, "PNG", source);
  std::size_t size = 0;
  if (int e = spng_decoded_image_size(png.get(), SPNG_FMT_RGBA8, &size)) fail(e);
  out.rgba.resize(size);
  if (int e = spng_decode_image(png.get(), out.rgba.data(), size, SPNG_FMT_RGBA8, SPNG_DECODE_TRNS)) fail(e);
  return out;
}

// Whether the JPEG's first frame header is progressive (SOF2, SOF6, SOF10 or SOF14), walking its marker segments.
bool is_progressive_jpeg(std::span<const unsigned char> bytes) {
  std::size_t at = 2;
  while (at + 4 <= bytes.size()) {
    if (bytes[at] != 0xff) return false;
    const unsigned marker = bytes[at + 1];
    if (marker == 0xff) {  // fill byte
      ++at;
      continue;
    }
    if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc)
      return (marker & 3) == 2;
    at += 2 + (bytes[at + 2] << 8 | bytes[at + 3]);
  }
  return false;
}

DecodedImage decode_jpeg(std::span<const unsigned char> bytes, int max_size, const std::string& source) {
  std::unique_ptr<void, int (*)(tjhandle)> jpeg(tjInitDecompress(), &tjDestroy);
  if (!jpeg) throw std::bad_alloc();
  if (bytes.size() > ULONG_MAX) throw InputError(source, "JPEG file too large");
  const auto fail = [&] {
    throw InputError(source, std::string("cannot decode JPEG (libjpeg-turbo: ") + tjGetErrorStr2(jpeg.get()) + ")");
  };
  int width = 0, height = 0, subsampling = 0, colorspace = 0;
  if (tjDecompressHeader3(jpeg.get(), bytes.data(), static_cast<unsigned long>(bytes.size()), &width, &height,
                          &subsampling, &colorspace) != 0)
    fail();
  if (width < 1 || height < 1) throw InputError(source, "cannot decode JPEG (libjpeg-turbo: no image size found)");
  check_size(width, height, max_size, source);
  const std::uint64_t per_byte = is_progressive_jpeg(bytes) ? 8 * kDeflateRatio : kBaselineJpegTexelsPerByte;
  check_backed(texels(width, height), per_byte * bytes.size(), width, height, "JPEG", source);
  DecodedImage out{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
  // A warning (a truncated or slightly corrupt stream) still leaves a whole image, as viewers show it.
  if (tjDecompress2(jpeg.get(), bytes.data(), static_cast<unsigned long>(bytes.size()), out.rgba.data(), width, 0,
                    height, TJPF_RGBA, 0) != 0 &&
      tjGetErrorCode(jpeg.get()) != TJERR_WARNING)
    fail();
  return out;
}

#endif

DecodedImage decode_with_stb(std::span<const unsigned char> bytes, int max_size, const std::string& source) {
  if (bytes.size() > INT_MAX) throw InputError(source, "image file too large");
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    throw InputError(
        source, std::string("not a readable PNG, JPEG, TGA or BMP image (stb_image: ") + stbi_failure_reason() + ")");
  check_size(width, height, max_size, source);
  if (is_png(bytes) || is_jpeg(bytes))  // without libspng and TurboJPEG: the loosest bound of either
    check_backed(texels(width, height), 8 * kDeflateRatio * bytes.size(), width, height, "image", source);
  else
    check_stb_bounds(bytes, width, height, source);
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 4), &stbi_image_free);
  if (!pixels) throw InputError(source, std::string("cannot decode image (stb_image: ") + stbi_failure_reason() + ")");
  const std::size_t size = static_cast<std::size_t>(width) * height * 4;
  return DecodedImage{width, height, std::vector<std::uint8_t>(pixels.get(), pixels.get() + size)};
}

}  // namespace

DecodedImage decode_image(std::span<const unsigned char> bytes, int max_size, const std::string& source) {
#ifndef FACET_NO_IMAGE_CODECS
  if (is_png(bytes)) return decode_png(bytes, max_size, source);
  if (is_jpeg(bytes)) return decode_jpeg(bytes, max_size, source);
#endif
  return decode_with_stb(bytes, max_size, source);
}

std::optional<std::pair<int, int>> image_size(std::span<const unsigned char> bytes) {
#ifndef FACET_NO_IMAGE_CODECS
  if (is_png(bytes)) {
    std::unique_ptr<spng_ctx, void (*)(spng_ctx*)> png(spng_ctx_new(0), &spng_ctx_free);
    spng_ihdr header{};
    if (!png || spng_set_png_buffer(png.get(), bytes.data(), bytes.size()) != 0 ||
        spng_get_ihdr(png.get(), &header) != 0 || header.width > INT_MAX || header.height > INT_MAX)
      return std::nullopt;
    return std::pair{static_cast<int>(header.width), static_cast<int>(header.height)};
  }
  if (is_jpeg(bytes)) {
    std::unique_ptr<void, int (*)(tjhandle)> jpeg(tjInitDecompress(), &tjDestroy);
    int width = 0, height = 0, subsampling = 0, colorspace = 0;
    if (!jpeg || bytes.size() > ULONG_MAX ||
        tjDecompressHeader3(jpeg.get(), bytes.data(), static_cast<unsigned long>(bytes.size()), &width, &height,
                            &subsampling, &colorspace) != 0)
      return std::nullopt;
    return std::pair{width, height};
  }
#endif
  int width = 0, height = 0, channels = 0;
  if (bytes.size() > INT_MAX ||
      !stbi_info_from_memory(bytes.data(), static_cast<int>(bytes.size()), &width, &height, &channels))
    return std::nullopt;
  return std::pair{width, height};
}

}  // namespace facet
