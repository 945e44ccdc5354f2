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

// How many texels a byte of a file can describe: deflate tops out near 1,032:1 (8,256 texels a byte for a 1-bit
// PNG, 258 for RGBA), JPEG near 256 texels a byte, and the run-length codes of TGA and BMP at 128. A header claiming
// more describes texels the file does not hold: a 72-byte BMP claiming 9,985 x 8,229 texels would otherwise be
// decoded into 330 MB of guesses.
constexpr std::uint64_t kMaxTexelsPerByte = 8192;    // PNG and JPEG
constexpr std::uint64_t kMaxTexelsPerByteRle = 256;  // TGA and BMP

void check_size(int width, int height, int max_size, std::size_t file_bytes, const std::string& source,
                std::uint64_t max_texels_per_byte = kMaxTexelsPerByte) {
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw InputError(source, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels; the limit is 1.." + std::to_string(max_size) + " per side");
  const std::uint64_t texels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (texels > (1u << 20) && texels / max_texels_per_byte > file_bytes)
    throw InputError(source, "image claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels, more than its " + std::to_string(file_bytes) + " bytes can hold");
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
  check_size(out.width, out.height, max_size, bytes.size(), source);
  std::size_t size = 0;
  if (int e = spng_decoded_image_size(png.get(), SPNG_FMT_RGBA8, &size)) fail(e);
  out.rgba.resize(size);
  if (int e = spng_decode_image(png.get(), out.rgba.data(), size, SPNG_FMT_RGBA8, SPNG_DECODE_TRNS)) fail(e);
  return out;
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
  check_size(width, height, max_size, bytes.size(), source);
  DecodedImage out{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
  // A warning (a truncated or slightly corrupt stream) still leaves a whole image, as viewers show it.
  if (tjDecompress2(jpeg.get(), bytes.data(), static_cast<unsigned long>(bytes.size()), out.rgba.data(), width, 0,
                    height, TJPF_RGBA, 0) != 0 &&
      tjGetErrorCode(jpeg.get()) != TJERR_WARNING)
    fail();
  return out;
}

#endif

DecodedImage decode_with_stb(std::span<const unsigned char> bytes, int max_size, const std::string& source,
                             std::uint64_t max_texels_per_byte) {
  if (bytes.size() > INT_MAX) throw InputError(source, "image file too large");
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    throw InputError(
        source, std::string("not a readable PNG, JPEG, TGA or BMP image (stb_image: ") + stbi_failure_reason() + ")");
  check_size(width, height, max_size, bytes.size(), source, max_texels_per_byte);
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 4), &stbi_image_free);
  if (!pixels) throw InputError(source, std::string("cannot decode image (stb_image: ") + stbi_failure_reason() + ")");
  const std::size_t size = static_cast<std::size_t>(width) * height * 4;
  return DecodedImage{width, height, std::vector<std::uint8_t>(pixels.get(), pixels.get() + size)};
}

bool is_png(std::span<const unsigned char> bytes) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin());
}

bool is_jpeg(std::span<const unsigned char> bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

}  // namespace

DecodedImage decode_image(std::span<const unsigned char> bytes, int max_size, const std::string& source) {
#ifndef FACET_NO_IMAGE_CODECS
  if (is_png(bytes)) return decode_png(bytes, max_size, source);
  if (is_jpeg(bytes)) return decode_jpeg(bytes, max_size, source);
  return decode_with_stb(bytes, max_size, source, kMaxTexelsPerByteRle);
#else
  const bool compressed = is_png(bytes) || is_jpeg(bytes);
  return decode_with_stb(bytes, max_size, source, compressed ? kMaxTexelsPerByte : kMaxTexelsPerByteRle);
#endif
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
