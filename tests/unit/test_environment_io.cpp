// test_environment_io.cpp - reading environment images: OpenEXR (facet's own files and the C++ library's, scanline
// and tiled, every compression, half, float and uint channels) and Radiance .hdr (flat and run-length), and the
// errors each bad file gives.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfTiledOutputFile.h>
#include <gtest/gtest.h>
#include <half.h>

#include "facet/environment.hpp"
#include "facet/error.hpp"
#include "job/io/exr.hpp"
#include "support/scratch_dir.hpp"

namespace facet::environment_io_tests {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir() { return test::scratch_dir("environment_io"); }

void write_bytes(const fs::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  ASSERT_TRUE(out.good()) << path;
}
void write_bytes(const fs::path& path, const std::string& bytes) { write_bytes(path, bytes.data(), bytes.size()); }
void write_bytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  write_bytes(path, bytes.data(), bytes.size());
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Values laid out pixel by pixel, `channels` a pixel, all distinct and not negative.
std::vector<float> test_values(int width, int height, int channels) {
  std::vector<float> values(static_cast<std::size_t>(width * height * channels));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.25f * static_cast<float>(i) + 0.125f;
  return values;
}

// Reading `path` throws an InputError whose message names the file and contains `detail`.
void expect_input_error(const fs::path& path, const std::string& detail) {
  try {
    (void)read_environment_image(path);
    ADD_FAILURE() << path << " was read without error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(detail), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(EnvironmentIo, ExrRoundTripRgb) {
  const fs::path path = scratch_dir() / "rgb.exr";
  const std::vector<float> values = test_values(5, 3, 3);
  write_bytes(path, encode_exr(5, 3, 3, values));
  const EnvironmentImage image = read_environment_image(path);
  ASSERT_EQ(image.width, 5);
  ASSERT_EQ(image.height, 3);
  ASSERT_EQ(image.texels.size(), 15u);
  for (std::size_t i = 0; i < image.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(image.texels[i][c], values[3 * i + static_cast<std::size_t>(c)]) << i;
}

TEST(EnvironmentIo, ExrRoundTripLuminanceIsGrey) {
  const fs::path path = scratch_dir() / "grey.exr";
  const std::vector<float> values = test_values(4, 6, 1);
  write_bytes(path, encode_exr(4, 6, 1, values));
  const EnvironmentImage image = read_environment_image(path);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 6);
  ASSERT_EQ(image.texels.size(), 24u);
  for (std::size_t i = 0; i < image.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(image.texels[i][c], values[i]) << i;
}

// Files written by OpenEXR's C++ library, compared with what that library reads from them: scanline and tiled
// (a mipmapped one among them), every compression, half, float and uint channels, a layer prefix, a data window
// away from the origin and tiles that overhang it, and channels that are not colour.
struct ExrCase {
  Imf::Compression compression;
  bool tiled;
  Imf::PixelType type;
  std::vector<std::string> names;  // sorted, as a file lists them
};

std::vector<float> write_and_read_back(const fs::path& path, const ExrCase& test, int width, int height) {
  const Imath::Box2i window(Imath::V2i(-3, 5), Imath::V2i(-3 + width - 1, 5 + height - 1));
  Imf::Header header(window, window);
  header.compression() = test.compression;
  const std::size_t texels = static_cast<std::size_t>(width * height);
  std::vector<std::vector<std::uint32_t>> planes(test.names.size(), std::vector<std::uint32_t>(texels));
  Imf::FrameBuffer frame;
  for (std::size_t c = 0; c < test.names.size(); ++c) {
    header.channels().insert(test.names[c], Imf::Channel(test.type));
    for (std::size_t i = 0; i < texels; ++i) {
      const float value = static_cast<float>((i * 7 + c * 13) % 50) / 8.0f;  // exact in half
      std::uint32_t& word = planes[c][i];
      if (test.type == Imf::UINT) {
        word = static_cast<std::uint32_t>((i * 3 + c) % 1000);
      } else if (test.type == Imf::FLOAT) {
        std::memcpy(&word, &value, 4);
      } else {
        const half h(value);
        const std::uint16_t bits = h.bits();
        std::memcpy(&word, &bits, 2);
      }
    }
    // A value a 4-byte word; a half one in its first two bytes.
    frame.insert(test.names[c],
                 Imf::Slice::Make(test.type, planes[c].data(), window, 4, 4 * static_cast<std::size_t>(width)));
  }
  if (test.tiled) {
    header.setTileDescription(
        Imf::TileDescription(16, 8, test.compression == Imf::ZIP_COMPRESSION ? Imf::MIPMAP_LEVELS : Imf::ONE_LEVEL));
    Imf::TiledOutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    for (int level = 0; level < out.numLevels(); ++level)
      out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
  } else {
    Imf::OutputFile out(path.c_str(), header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
  }
  // What the C++ library reads, as floats, R G B a pixel (Y in all three when there is no colour).
  std::vector<float> rgb(texels * 3, 0.0f);
  Imf::InputFile in(path.c_str());
  Imf::FrameBuffer read;
  bool colour = false;
  for (const std::string& name : test.names)
    for (const char* c : {"R", "G", "B"}) colour = colour || name == c || name.ends_with(std::string(".") + c);
  for (int k = 0; k < 3; ++k) {
    const std::string want = colour ? std::string(1, "RGB"[k]) : "Y";
    for (const std::string& name : test.names)
      if (name == want || name.ends_with("." + want)) {
        read.insert(name,
                    Imf::Slice::Make(Imf::FLOAT, rgb.data() + k, window, 12, 12 * static_cast<std::size_t>(width)));
        break;
      }
    if (!colour) break;
  }
  in.setFrameBuffer(read);
  in.readPixels(window.min.y, window.max.y);
  if (!colour)
    for (std::size_t i = 0; i < texels; ++i) rgb[3 * i + 1] = rgb[3 * i + 2] = rgb[3 * i];
  return rgb;
}

TEST(EnvironmentIo, ExrFromOpenExrLibrary) {
  const fs::path dir = scratch_dir();
  const std::vector<std::vector<std::string>> channel_sets = {{"A", "B", "G", "R"},
                                                              {"diffuse.B", "diffuse.G", "diffuse.R", "Z"},
                                                              {"G", "R", "Z"},
                                                              {"A", "R", "Z"},
                                                              {"Q", "Y", "Z"}};
  int cases = 0;
  for (const Imf::Compression compression :
       {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION, Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION,
        Imf::PXR24_COMPRESSION, Imf::B44_COMPRESSION, Imf::B44A_COMPRESSION})
    for (const bool tiled : {false, true})
      for (const Imf::PixelType type : {Imf::HALF, Imf::FLOAT, Imf::UINT})
        for (const std::vector<std::string>& names : channel_sets) {
          const ExrCase test{compression, tiled, type, names};
          const fs::path path = dir / ("case" + std::to_string(cases++) + ".exr");
          SCOPED_TRACE(path.string() + ": compression " + std::to_string(compression) + (tiled ? ", tiled" : "") +
                       ", pixel type " + std::to_string(type) + ", channels " + names[0] + " ...");
          const std::vector<float> expected = write_and_read_back(path, test, 37, 23);
          // The decoder itself: B44's loss can take a texel below 0, which read_environment_image rejects.
          const std::string bytes = read_file(path);
          int checked_width = 0, checked_height = 0, width = 0, height = 0;
          const std::vector<float> rgb = decode_exr_rgb(
              bytes.data(), bytes.size(), path.string(), [&](int w, int h) { checked_width = w, checked_height = h; },
              width, height);
          EXPECT_EQ(checked_width, 37);
          EXPECT_EQ(checked_height, 23);
          ASSERT_EQ(width, 37);
          ASSERT_EQ(height, 23);
          ASSERT_EQ(rgb.size(), expected.size());
          int wrong = 0;
          for (std::size_t i = 0; i < rgb.size(); ++i)
            if (rgb[i] != expected[i] && ++wrong <= 3)
              ADD_FAILURE() << "texel " << i / 3 << " channel " << i % 3 << ": " << rgb[i] << ", expected "
                            << expected[i];
          EXPECT_EQ(wrong, 0);
        }
}

// RGBE as Radiance writes it (Greg Ward's float2rgbe).
std::string rgbe(float r, float g, float b) {
  const float v = std::max({r, g, b});
  if (v < 1e-32f) return std::string(4, '\0');
  int e = 0;
  const float scale = std::frexp(v, &e) * 256.0f / v;
  return {static_cast<char>(static_cast<unsigned char>(r * scale)),
          static_cast<char>(static_cast<unsigned char>(g * scale)),
          static_cast<char>(static_cast<unsigned char>(b * scale)), static_cast<char>(e + 128)};
}

std::string hdr_header(int width, int height) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
}

void expect_near_rgbe(const glm::vec3& texel, float r, float g, float b) {
  // RGBE keeps 8 bits of mantissa for the largest component, so each is within 1/128 of it.
  const float tolerance = std::max({r, g, b}) / 128.0f;
  EXPECT_NEAR(texel.r, r, tolerance);
  EXPECT_NEAR(texel.g, g, tolerance);
  EXPECT_NEAR(texel.b, b, tolerance);
}

TEST(EnvironmentIo, HdrFlat) {
  const fs::path path = scratch_dir() / "flat.hdr";
  const float values[6][3] = {{1.0f, 0.5f, 0.25f},      {100.0f, 3.0f, 0.01f}, {0.0f, 0.0f, 0.0f},
                              {0.002f, 0.004f, 0.003f}, {7.5f, 7.5f, 7.5f},    {0.3f, 2000.0f, 1.0f}};
  std::string file = hdr_header(3, 2);
  for (const auto& v : values) file += rgbe(v[0], v[1], v[2]);
  write_bytes(path, file);
  const EnvironmentImage image = read_environment_image(path);
  ASSERT_EQ(image.width, 3);
  ASSERT_EQ(image.height, 2);
  ASSERT_EQ(image.texels.size(), 6u);
  for (int i = 0; i < 6; ++i)
    expect_near_rgbe(image.texels[static_cast<std::size_t>(i)], values[i][0], values[i][1], values[i][2]);
}

// A run-length file: each scanline 2 2 and its width, then each of R, G, B and E as runs and literals.
std::string rle_hdr(int width, int height) {
  std::string file = hdr_header(width, height);
  for (int y = 0; y < height; ++y) {
    file += {2, 2, static_cast<char>(width >> 8), static_cast<char>(width & 0xff)};
    for (int channel = 0; channel < 4; ++channel) {
      // R, G and B (64 + 32 y + channel) / 128: an exponent byte of 129 scales by 2^(129 - 136).
      const char value = static_cast<char>(channel == 3 ? 129 : 64 + 32 * y + channel);
      file += {static_cast<char>(128 + width - 2), value};  // a run
      file += {2, value, value};                            // two literals
    }
  }
  return file;
}

TEST(EnvironmentIo, HdrRunLength) {
  const fs::path path = scratch_dir() / "rle.hdr";
  write_bytes(path, rle_hdr(10, 2));
  const EnvironmentImage image = read_environment_image(path);
  ASSERT_EQ(image.width, 10);
  ASSERT_EQ(image.height, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 10; ++x) {
      const glm::vec3 t = image.texels[static_cast<std::size_t>(y * 10 + x)];
      for (int c = 0; c < 3; ++c) EXPECT_EQ(t[c], static_cast<float>(64 + 32 * y + c) / 128.0f) << x << ", " << y;
    }
}

TEST(EnvironmentIo, MissingFile) { expect_input_error(scratch_dir() / "missing.exr", "no such file"); }

TEST(EnvironmentIo, EmptyFiles) {
  const fs::path dir = scratch_dir();
  for (const char* name : {"empty.hdr", "empty.exr"}) {
    write_bytes(dir / name, std::string());
    expect_input_error(dir / name, "empty");
  }
}

TEST(EnvironmentIo, TruncatedHdr) {
  const fs::path dir = scratch_dir();
  std::string flat = hdr_header(3, 2);
  for (int i = 0; i < 6; ++i) flat += rgbe(1.0f, 2.0f, 3.0f);
  write_bytes(dir / "flat.hdr", flat.substr(0, flat.size() - 5));
  expect_input_error(dir / "flat.hdr", "truncated");
  // stb_image alone would loop for ever on this one.
  const std::string rle = rle_hdr(10, 2);
  write_bytes(dir / "rle.hdr", rle.substr(0, rle.size() - 3));
  expect_input_error(dir / "rle.hdr", "truncated");
}

TEST(EnvironmentIo, TruncatedExr) {
  const fs::path path = scratch_dir() / "truncated.exr";
  const std::vector<std::uint8_t> bytes = encode_exr(64, 32, 3, test_values(64, 32, 3));
  write_bytes(path, bytes.data(), bytes.size() / 2);
  expect_input_error(path, "OpenEXR: ");
}

TEST(EnvironmentIo, SizeTheFileCannotHold) {
  const fs::path path = scratch_dir() / "huge.hdr";
  std::string file = hdr_header(16000, 16000);
  file.resize(100, '\x80');
  write_bytes(path, file);
  expect_input_error(path, "more than its 100 bytes can hold");
}

TEST(EnvironmentIo, NanAndNegativeTexels) {
  const fs::path dir = scratch_dir();
  std::vector<float> values = test_values(4, 2, 3);
  values[3 * 5 + 1] = std::numeric_limits<float>::quiet_NaN();
  write_bytes(dir / "nan.exr", encode_exr(4, 2, 3, values));
  expect_input_error(dir / "nan.exr", "texel (1, 1) is negative, NaN or infinite");
  values = test_values(4, 2, 3);
  values[3 * 2 + 2] = -1.0f;
  write_bytes(dir / "negative.exr", encode_exr(4, 2, 3, values));
  expect_input_error(dir / "negative.exr", "texel (2, 0) is negative");
}

TEST(EnvironmentIo, WrongExtension) {
  const fs::path path = scratch_dir() / "sky.png";
  write_bytes(path, hdr_header(1, 1) + rgbe(1.0f, 1.0f, 1.0f));
  expect_input_error(path, "Radiance .hdr or an OpenEXR .exr");
}

}  // namespace
}  // namespace facet::environment_io_tests
