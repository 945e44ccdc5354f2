// bits.hpp - std::bit_cast and the byte order for every standard library facet builds with (Emscripten's too).
#pragma once

#include <type_traits>

namespace facet::detail {

// std::bit_cast's contract, on the builtin that GCC and Clang build it on (Debian's Emscripten libc++ lacks it).
template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
  static_assert(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>);
  return __builtin_bit_cast(To, from);
}

// std::endian::native == std::endian::little, which that libc++ lacks as well.
inline constexpr bool kLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

}  // namespace facet::detail
