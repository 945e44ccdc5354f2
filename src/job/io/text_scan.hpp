// text_scan.hpp - whitespace-separated tokens and strict numbers for the ASCII model readers (PLY, STL).
#pragma once

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include "job/io/loaders.hpp"

namespace facet {

// Space, \t, \n, \v, \f, \r: what C's isspace accepts in the "C" locale, without its table lookup.
inline bool is_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

// Reads tokens forward through a text, counting lines so that messages can say where a token was.
class TextCursor {
 public:
  TextCursor(const char* at, const char* end, std::size_t line) : p_(at), end_(end), line_(line) {}

  // The next token, or an empty view at the end of the text; line() is then the token's line (at the end, the
  // last token's, not the empty one after a final line break).
  std::string_view next() {
    if (at_end()) return {};
    const char* start = p_;
    while (p_ != end_ && !is_space(*p_)) ++p_;
    return {start, static_cast<std::size_t>(p_ - start)};
  }

  // Moves to the end of the current line (to skip an STL solid's name, which may hold spaces or be missing).
  void skip_line() {
    while (p_ != end_ && *p_ != '\n') ++p_;
  }

  // Skips whitespace; true if nothing else is left.
  bool at_end() {
    std::size_t breaks = 0;
    while (p_ != end_ && is_space(*p_)) {
      breaks += *p_ == '\n';
      ++p_;
    }
    if (p_ == end_) return true;
    line_ += breaks;
    return false;
  }

  std::size_t line() const { return line_; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

 private:
  const char* p_;
  const char* end_;
  std::size_t line_;
};

// std::from_chars takes no leading '+', which some writers emit.
inline std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  return token;
}

// A whole token as a float or double (correctly rounded; "nan" and "inf" are accepted here and refused by the
// callers that need finite values). Out-of-range exponents, which from_chars refuses without a value, read as strtod
// does: infinity for overflow, zero or a denormal for underflow.
template <class Real>
bool parse_real(std::string_view token, Real& out) {
  token = without_plus(token);
#if defined(__cpp_lib_to_chars)
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, out);
  if (ptr != end) return false;
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(token);
    if constexpr (sizeof(Real) == sizeof(float)) out = std::strtof(copy.c_str(), nullptr);
    else out = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
#else
  // A libc++ without floating-point from_chars (Emscripten's): strtod on a copy, refusing what from_chars refuses
  // and strtod takes (leading space or '+', hexadecimal).
  const std::size_t sign = !token.empty() && token[0] == '-' ? 1 : 0;
  if (token.size() <= sign || token[sign] == '+' || token[sign] == '-' ||
      std::isspace(static_cast<unsigned char>(token[sign])) ||
      (token.size() > sign + 1 && token[sign] == '0' && (token[sign + 1] == 'x' || token[sign + 1] == 'X')))
    return false;
  const std::string copy(token);
  char* stop = nullptr;
  if constexpr (sizeof(Real) == sizeof(float)) out = std::strtof(copy.c_str(), &stop);
  else out = std::strtod(copy.c_str(), &stop);
  return stop == copy.c_str() + copy.size();
#endif
}

// A double as the nearest float, infinite beyond float's range (a plain conversion would be undefined there).
inline float narrow(double d) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (d > kMax) return std::numeric_limits<float>::infinity();
  if (d < -kMax) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(d);
}

// A whole token as a decimal integer (no fraction, no exponent).
inline bool parse_integer(std::string_view token, std::int64_t& out) {
  token = without_plus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, out);
  return ec == std::errc() && ptr == end;
}

// A token from the file, quoted and shortened for a message.
inline std::string in_quotes(std::string_view token) {
  std::string out(1, '\'');  // appended rather than "'" + ...: GCC 12 warns falsely (-Wrestrict) on that
  out += printable(token.substr(0, 40));
  out += token.size() > 40 ? "...'" : "'";
  return out;
}

}  // namespace facet
