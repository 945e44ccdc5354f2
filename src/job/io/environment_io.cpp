// environment_io.cpp - reading environment images: Radiance .hdr through stb_image, OpenEXR through its C core.
// A build without OpenEXR (the browser page's, FACET_NO_OPENEXR) reads .hdr alone.
#include <climits>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "facet/environment.hpp"
#include "facet/error.hpp"
#include "core/file_util.hpp"
#ifndef FACET_NO_OPENEXR
#include "job/io/exr.hpp"
#endif
#include "scene/texture/stb.hpp"

namespace facet {

namespace {

// A Radiance file's run-length scanlines hold at most 127 texels in two bytes per channel (four channels), flat
// ones four bytes a texel: a header claiming more texels than 16 a byte describes what the file does not hold.
constexpr std::uint64_t kMaxHdrTexelsPerByte = 16;

void check_environment_size(int width, int height, std::size_t file_bytes, std::uint64_t max_texels_per_byte,
                            const std::string& source) {
  if (width < 1 || height < 1 || width > kMaxEnvironmentSize || height > kMaxEnvironmentSize)
    throw InputError(source, "environment image is " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels; the limit is 1.." + std::to_string(kMaxEnvironmentSize) + " per side");
  const std::uint64_t texels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (texels > 4096 && texels / max_texels_per_byte > file_bytes)
    throw InputError(source, "environment image claims " + std::to_string(width) + "x" + std::to_string(height) +
                                 " texels, more than its " + std::to_string(file_bytes) + " bytes can hold");
}

// Radiance is light: every texel must be finite and not negative.
void check_texels(const EnvironmentImage& image, const std::string& source) {
  for (std::size_t i = 0; i < image.texels.size(); ++i) {
    const glm::vec3 t = image.texels[i];
    for (int c = 0; c < 3; ++c)
      if (!(t[c] >= 0.0f) || !std::isfinite(t[c]))
        throw InputError(source, "texel (" + std::to_string(i % static_cast<std::size_t>(image.width)) + ", " +
                                     std::to_string(i / static_cast<std::size_t>(image.width)) +
                                     ") is negative, NaN or infinite");
  }
}

// stb_image (2.27) reads a Radiance file's pixels without checking for the end of the file: a truncated flat file
// gives texels from uninitialised memory, and a truncated run-length one loops for ever (at the end it reads a run
// of length 0, which never advances). This walks the pixels as stb_image will read them and throws for a file that
// ends early or holds a run of length 0; what else stb_image rejects, it reports itself.
void check_hdr_pixels(const std::vector<unsigned char>& bytes, int width, int height, const std::string& source) {
  const std::size_t end = bytes.size();
  std::size_t pos = 0;
  // The header as stb_image reads it: the identifier line, lines up to an empty one (or one starting with a NUL
  // byte), then the resolution line.
  const auto line = [&] {  // whether it was empty
    const std::size_t start = pos;
    while (pos < end && bytes[pos] != '\n') ++pos;
    const bool empty = pos == start || bytes[start] == '\0';
    if (pos < end) ++pos;
    return empty;
  };
  line();
  while (pos < end && !line()) {
  }
  line();
  const auto take = [&](std::uint64_t count) {
    if (end - pos < count)
      throw InputError(source, "truncated: the Radiance pixel data ends early, at byte " + std::to_string(end));
    pos += static_cast<std::size_t>(count);
  };
  const std::uint64_t texels = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  if (width < 8 || width >= 32768) {  // flat: R, G, B and E a texel
    take(4 * texels);
    return;
  }
  for (int row = 0; row < height; ++row) {
    take(4);
    const unsigned char* head = &bytes[pos - 4];
    // Not a run-length scanline: stb_image reads this texel and every one after it flat.
    if (head[0] != 2 || head[1] != 2 || (head[2] & 0x80)) {
      take(4 * (texels - 1));
      return;
    }
    if (((head[2] << 8) | head[3]) != width) return;  // stb_image: "invalid decoded scanline length"
    for (int channel = 0; channel < 4; ++channel)
      for (int x = 0; x < width;) {
        take(1);
        int count = bytes[pos - 1];
        if (count > 128) {  // a run of one value
          take(1);
          count -= 128;
        } else if (count == 0) {
          throw InputError(source,
                           "malformed Radiance run-length data: a run of length 0 at byte " + std::to_string(pos - 1));
        } else {  // literal values
          if (count <= width - x) take(static_cast<std::uint64_t>(count));
        }
        if (count > width - x) return;  // stb_image: "bad RLE data in HDR"
        x += count;
      }
  }
}

EnvironmentImage read_hdr(const std::filesystem::path& path, const std::string& source) {
  const std::vector<unsigned char> bytes = read_image_file(path);
  const int length = static_cast<int>(bytes.size());
  if (!stbi_is_hdr_from_memory(bytes.data(), length)) throw InputError(source, "not a Radiance .hdr file");
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    throw InputError(source, std::string("malformed Radiance header (stb_image: ") + stbi_failure_reason() + ")");
  check_environment_size(width, height, bytes.size(), kMaxHdrTexelsPerByte, source);
  check_hdr_pixels(bytes, width, height, source);
  std::unique_ptr<float, void (*)(void*)> pixels(
      stbi_loadf_from_memory(bytes.data(), length, &width, &height, &channels, 3), &stbi_image_free);
  if (!pixels)
    throw InputError(source, std::string("cannot decode Radiance image (stb_image: ") + stbi_failure_reason() + ")");
  EnvironmentImage image;
  image.width = width;
  image.height = height;
  image.texels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const float* p = pixels.get();
  for (glm::vec3& t : image.texels) t = glm::vec3(p[0], p[1], p[2]), p += 3;
  return image;
}

}  // namespace

EnvironmentImage read_environment_image(const std::filesystem::path& path) {
  const std::string source = path.string();
  const std::string extension = lower_extension(path);
  EnvironmentImage image;
  if (extension == ".hdr" || extension == ".pic") {
    image = read_hdr(path, source);
  } else if (extension == ".exr") {
#ifdef FACET_NO_OPENEXR
    // The browser page's build has no OpenEXR.
    throw InputError(source, "this build reads Radiance .hdr environments only");
#else
    const FileBytes bytes = read_regular_file(path, INT_MAX, source);
    int width = 0, height = 0;
    std::vector<float> rgb = decode_exr_rgb(
        bytes.data(), bytes.size(), source,
        [&](int w, int h) { check_environment_size(w, h, bytes.size(), kMaxExrTexelsPerByte, source); }, width, height);
    image.width = width;
    image.height = height;
    image.texels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (std::size_t i = 0; i < image.texels.size(); ++i)
      image.texels[i] = {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]};
#endif
  } else {
    throw InputError(source, "an environment must be a Radiance .hdr or an OpenEXR .exr file");
  }
  check_texels(image, source);
  return image;
}

}  // namespace facet
