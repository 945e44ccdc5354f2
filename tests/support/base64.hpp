// base64.hpp - Base64 text of bytes, for tests that write glTF files with data: URI buffers.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

namespace facet::test {

inline std::string base64(const std::string& bytes) {
  constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t count = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t chunk = 0;
    for (std::size_t k = 0; k < 3; ++k)
      chunk = chunk << 8 | (k < count ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= count ? kDigits[chunk >> (18 - 6 * k) & 63] : '=';
  }
  return out;
}

}  // namespace facet::test
