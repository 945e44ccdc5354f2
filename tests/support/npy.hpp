// npy.hpp - reading back the 4-byte-element .npy files facet writes, for tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace facet::test {

// The header and data of a little-endian 4-byte .npy file.
struct Npy {
  std::string header;
  std::vector<std::uint32_t> words;
};

inline Npy read_npy(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) throw std::runtime_error("not .npy");
  const std::size_t length = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  Npy npy{bytes.substr(10, length), std::vector<std::uint32_t>((bytes.size() - 10 - length) / 4)};
  std::memcpy(npy.words.data(), bytes.data() + 10 + length, npy.words.size() * 4);
  return npy;
}

}  // namespace facet::test
