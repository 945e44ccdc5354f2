// gif.hpp - animated GIF encoding (giflib), with one palette chosen for all frames of the animation.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace facet {

// The GIF file of `frames` (each width * height RGBA bytes, top row first; alpha is ignored), looping forever,
// each shown for delay_centiseconds. One 256-colour palette is chosen by median cut over every frame's pixels
// together, so colours do not change from frame to frame. Throws std::invalid_argument for no frames, frames of
// the wrong size or more pixels than giflib can quantize at once (2^32), std::runtime_error if giflib fails.
std::vector<std::uint8_t> encode_gif(int width, int height, std::span<const std::vector<std::uint8_t>> frames,
                                     int delay_centiseconds);

}  // namespace facet
