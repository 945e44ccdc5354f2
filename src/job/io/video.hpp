// video.hpp - MP4 (H.264) and WebM (VP9) encoding of rendered frames with FFmpeg's libraries.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace facet {

enum class VideoFormat { mp4, webm };

// The video file of `frames` (each width * height RGBA bytes, top row first; alpha is ignored), frame_seconds
// apart: H.264 in MP4 or VP9 in WebM, 4:2:0 BT.709 limited range, as players expect. 4:2:0 needs even sizes, so
// an odd width or height is padded by one column or row repeating the edge. The encoder runs on one thread, so
// the bytes depend only on the frames. Throws std::invalid_argument for no frames or frames of the wrong size,
// std::runtime_error naming the library's complaint when no encoder is available or encoding fails.
std::vector<std::uint8_t> encode_video(VideoFormat format, int width, int height,
                                       std::span<const std::vector<std::uint8_t>> frames, double frame_seconds);

}  // namespace facet
