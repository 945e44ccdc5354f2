// gif.cpp - animated GIFs through giflib: a median-cut palette over the whole animation, frames LZW-coded.
#include "job/io/gif.hpp"

#include <gif_lib.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace facet {

namespace {

int append_bytes(GifFileType* gif, const GifByteType* data, int length) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(gif->UserData);
  out->insert(out->end(), data, data + length);
  return length;
}

[[noreturn]] void gif_failed(const char* what, int error) {
  const char* reason = GifErrorString(error);
  throw std::runtime_error(std::string("GIF encoding: ") + what + ": " + (reason ? reason : "unknown error"));
}

}  // namespace

std::vector<std::uint8_t> encode_gif(int width, int height, std::span<const std::vector<std::uint8_t>> frames,
                                     int delay_centiseconds) {
  if (frames.empty()) throw std::invalid_argument("GIF: no frames");
  if (width < 1 || height < 1 || width > 65535 || height > 65535)
    throw std::invalid_argument("GIF: frames of " + std::to_string(width) + "x" + std::to_string(height));
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const std::size_t total = pixels * frames.size();
  if (total / frames.size() != pixels ||
      static_cast<std::uint64_t>(height) * frames.size() > std::numeric_limits<unsigned>::max())
    throw std::invalid_argument("GIF: too many pixels to choose one palette for");
  // giflib quantizes one image: the frames stacked one above the other are that image.
  std::vector<GifByteType> red(total), green(total), blue(total), indices(total);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != pixels * 4) throw std::invalid_argument("GIF: a frame of the wrong size");
    for (std::size_t p = 0; p < pixels; ++p) {
      red[f * pixels + p] = frames[f][4 * p];
      green[f * pixels + p] = frames[f][4 * p + 1];
      blue[f * pixels + p] = frames[f][4 * p + 2];
    }
  }
  int colors = 256;
  GifColorType palette[256] = {};
  if (GifQuantizeBuffer(static_cast<unsigned>(width), static_cast<unsigned>(height * frames.size()), &colors,
                        red.data(), green.data(), blue.data(), indices.data(), palette) == GIF_ERROR)
    throw std::runtime_error("GIF encoding: the palette could not be chosen");

  std::vector<std::uint8_t> bytes;
  int error = 0;
  GifFileType* gif = EGifOpen(&bytes, append_bytes, &error);
  if (!gif) gif_failed("open", error);
  ColorMapObject* map = GifMakeMapObject(256, palette);
  const auto fail = [&](const char* what) {
    const int code = gif->Error;
    GifFreeMapObject(map);
    EGifCloseFile(gif, &error);
    gif_failed(what, code);
  };
  if (!map) fail("colour map");
  EGifSetGifVersion(gif, true);
  if (EGifPutScreenDesc(gif, width, height, 8, 0, map) == GIF_ERROR) fail("screen");
  // NETSCAPE2.0: loop forever.
  const GifByteType application[] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
  const GifByteType loop[] = {1, 0, 0};
  if (EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif, sizeof application, application) == GIF_ERROR ||
      EGifPutExtensionBlock(gif, sizeof loop, loop) == GIF_ERROR || EGifPutExtensionTrailer(gif) == GIF_ERROR)
    fail("loop extension");
  GraphicsControlBlock control{};
  control.DisposalMode = DISPOSE_DO_NOT;
  control.DelayTime = delay_centiseconds;
  control.TransparentColor = NO_TRANSPARENT_COLOR;
  GifByteType extension[4];
  EGifGCBToExtension(&control, extension);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, sizeof extension, extension) == GIF_ERROR) fail("frame delay");
    if (EGifPutImageDesc(gif, 0, 0, width, height, false, nullptr) == GIF_ERROR) fail("frame");
    for (int y = 0; y < height; ++y)
      if (EGifPutLine(gif, indices.data() + f * pixels + static_cast<std::size_t>(y) * width, width) == GIF_ERROR)
        fail("frame data");
  }
  GifFreeMapObject(map);
  if (EGifCloseFile(gif, &error) == GIF_ERROR) gif_failed("close", error);
  return bytes;
}

}  // namespace facet
