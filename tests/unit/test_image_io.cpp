// test_image_io.cpp - PNG write/read round trips, .npy layout, and atomic writes that leave nothing on failure.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "support/scratch_dir.hpp"

namespace facet::image_io_tests {
namespace {

std::filesystem::path scratch_dir() { return test::scratch_dir("image_io"); }

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::uint8_t> random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> v(n);
  for (auto& b : v) b = static_cast<std::uint8_t>(byte(rng));
  return v;
}

TEST(ImageIoPng, RgbaRoundTrip) {
  const std::filesystem::path path = scratch_dir() / "round_trip.png";
  const std::vector<std::uint8_t> pixels = random_bytes(7 * 5 * 4, 1);
  write_png(path, 7, 5, pixels);
  int w = 0, h = 0;
  EXPECT_EQ(read_png(path, w, h), pixels);
  EXPECT_EQ(w, 7);
  EXPECT_EQ(h, 5);
  const std::string file = read_bytes(path);
  ASSERT_GT(file.size(), 26u);
  EXPECT_EQ(file.substr(0, 8), std::string("\x89PNG\r\n\x1a\n"));
  EXPECT_EQ(file[25], 6);                                                               // IHDR colour type 6: RGBA
  EXPECT_EQ(names_in(path.parent_path()), std::vector<std::string>{"round_trip.png"});  // no temporary left
}

// Large enough for several deflate blocks, with runs (rows repeating, as backgrounds do) and noise between them;
// every byte must come back, and a grey PNG must be colour type 0.
TEST(ImageIoPng, LargeImagesAndGreyRoundTrip) {
  const int width = 613, height = 411;
  std::vector<std::uint8_t> pixels = random_bytes(static_cast<std::size_t>(width) * height * 4, 3);
  for (int y = 100; y < 300; ++y)
    std::copy_n(pixels.begin() + 99 * width * 4, width * 4,
                pixels.begin() + static_cast<std::ptrdiff_t>(y) * width * 4);
  const std::filesystem::path path = scratch_dir() / "large.png";
  write_png(path, width, height, pixels);
  int w = 0, h = 0;
  EXPECT_EQ(read_png(path, w, h), pixels);
  const std::vector<std::uint8_t> grey = random_bytes(static_cast<std::size_t>(width) * height, 4);
  write_png_gray(path, width, height, grey);
  EXPECT_EQ(read_bytes(path)[25], 0);  // IHDR colour type 0: grey
  const std::vector<std::uint8_t> back = read_png(path, w, h);
  for (std::size_t i = 0; i < grey.size(); ++i) ASSERT_EQ(back[4 * i], grey[i]) << i;
}

// Bands of rows compressed on several threads join into one stream that decodes to every byte, RGBA and RGB, with
// band edges inside runs and inside noise.
TEST(ImageIoPng, BandsOnSeveralThreadsRoundTrip) {
  const int width = 1500, height = 1001;
  std::vector<std::uint8_t> pixels = random_bytes(static_cast<std::size_t>(width) * height * 4, 5);
  for (int y = 150; y < 700; ++y)
    std::copy_n(pixels.begin() + 149 * width * 4, width * 4,
                pixels.begin() + static_cast<std::ptrdiff_t>(y) * width * 4);
  const std::filesystem::path path = scratch_dir() / "bands.png";
  for (const int threads : {1, 2, 3, 8}) {
    write_png(path, width, height, pixels, true, threads);
    int w = 0, h = 0;
    ASSERT_EQ(read_png(path, w, h), pixels) << threads << " threads";
    write_png(path, width, height, pixels, false, threads);
    const std::vector<std::uint8_t> back = read_png(path, w, h);
    ASSERT_EQ(back.size(), pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i)
      ASSERT_EQ(back[i], i % 4 == 3 ? 255 : pixels[i]) << threads << " threads, byte " << i;
  }
}

TEST(ImageIoPng, RgbWithoutAlpha) {
  const std::filesystem::path path = scratch_dir() / "rgb.png";
  const std::vector<std::uint8_t> pixels = random_bytes(3 * 4 * 4, 2);
  write_png(path, 3, 4, pixels, /*keep_alpha=*/false);
  EXPECT_EQ(read_bytes(path)[25], 2);  // IHDR colour type 2: RGB
  int w = 0, h = 0;
  const std::vector<std::uint8_t> back = read_png(path, w, h);
  ASSERT_EQ(back.size(), pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) EXPECT_EQ(back[i], i % 4 == 3 ? 255 : pixels[i]) << i;
}

// The filter works on several pixels at a time: narrow images leave every kind of row end, in RGBA, RGB and grey.
TEST(ImageIoPng, EveryRowEndRoundTrips) {
  const std::filesystem::path path = scratch_dir() / "narrow.png";
  for (int width = 1; width <= 11; ++width) {
    const int height = 3;
    const std::vector<std::uint8_t> pixels = random_bytes(static_cast<std::size_t>(width) * height * 4, 40 + width);
    int w = 0, h = 0;
    write_png(path, width, height, pixels, true);
    ASSERT_EQ(read_png(path, w, h), pixels) << width;
    write_png(path, width, height, pixels, false);
    std::vector<std::uint8_t> opaque = pixels;
    for (std::size_t i = 3; i < opaque.size(); i += 4) opaque[i] = 255;
    ASSERT_EQ(read_png(path, w, h), opaque) << width;
    const std::vector<std::uint8_t> grey(pixels.begin(), pixels.begin() + width * height);
    write_png_gray(path, width, height, grey);
    const std::vector<std::uint8_t> back = read_png(path, w, h);
    for (std::size_t i = 0; i < grey.size(); ++i) ASSERT_EQ(back[4 * i], grey[i]) << width << ", pixel " << i;
  }
}

TEST(ImageIoPng, FramebufferTopRowFirstAndOverwrite) {
  const std::filesystem::path path = scratch_dir() / "framebuffer.png";
  Framebuffer fb(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      fb.mutable_color()[static_cast<std::size_t>(y) * 4 + x] = pack_rgba8(glm::vec4(x / 3.0f, y / 2.0f, 0.5f, 1.0f));
  write_png(path, 1, 1, std::vector<std::uint8_t>{1, 2, 3, 4});  // an older file, replaced below
  write_png(path, fb);
  int w = 0, h = 0;
  const std::vector<std::uint8_t> back = read_png(path, w, h);
  EXPECT_EQ(w, 4);
  EXPECT_EQ(h, 3);
  EXPECT_EQ(back, fb.rgba8());
  EXPECT_EQ(back[1], 0);                  // row 0 of the framebuffer (green 0) is the file's first row
  EXPECT_EQ(back[(2 * 4) * 4 + 1], 255);  // the last row has green 255
}

TEST(ImageIoPng, BadSizesAreRejected) {
  const std::filesystem::path path = scratch_dir() / "bad.png";
  EXPECT_THROW(write_png(path, 2, 2, std::vector<std::uint8_t>(15)), std::invalid_argument);
  EXPECT_THROW(write_png(path, 0, 2, std::vector<std::uint8_t>{}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(ImageIoPng, MissingDirectoryThrowsAndLeavesNothing) {
  const std::filesystem::path dir = scratch_dir();
  const std::filesystem::path path = dir / "no_such_dir" / "out.png";
  try {
    write_png(path, 1, 1, std::vector<std::uint8_t>{1, 2, 3, 4});
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
    EXPECT_NE(what.find("No such file"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path.parent_path()));
  EXPECT_TRUE(names_in(dir).empty());
}

TEST(ImageIoPng, FailedRenameCleansUpTheTemporary) {
  // The target is an existing directory: the temporary is written, the rename fails, the temporary goes.
  const std::filesystem::path dir = scratch_dir();
  const std::filesystem::path target = dir / "taken.png";
  std::filesystem::create_directory(target);
  EXPECT_THROW(write_png(target, 1, 1, std::vector<std::uint8_t>{1, 2, 3, 4}), std::runtime_error);
  EXPECT_TRUE(std::filesystem::is_directory(target));
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"taken.png"});
}

TEST(ImageIoPng, ReadErrorsNameTheFile) {
  const std::filesystem::path dir = scratch_dir();
  for (const std::string name : {"missing.png", "garbage.png"}) {
    if (name == "garbage.png") std::ofstream(dir / name) << "not a png";
    int w = 0, h = 0;
    try {
      (void)read_png(dir / name, w, h);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind((dir / name).string() + ": ", 0), 0u) << e.what();
    }
  }
}

TEST(ImageIoNpy, HeaderAndPayload) {
  const std::filesystem::path path = scratch_dir() / "depth.npy";
  const std::vector<float> values = {0.0f, 0.25f, 1.0f, -2.5f, 1.0f / 3.0f, 1e-30f};
  write_npy(path, 3, 2, values);
  const std::string file = read_bytes(path);
  ASSERT_GE(file.size(), 10u);
  EXPECT_EQ(file.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header_len = static_cast<unsigned char>(file[8]) | static_cast<unsigned char>(file[9]) << 8;
  EXPECT_EQ((10 + header_len) % 64, 0u);
  ASSERT_EQ(file.size(), 10 + header_len + values.size() * 4);
  const std::string header = file.substr(10, header_len);
  const std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }";
  EXPECT_EQ(header.substr(0, dict.size()), dict);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_EQ(header.find_first_not_of(' ', dict.size()), header.size() - 1);  // spaces, then the newline
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::uint32_t bits = 0;
    for (int b = 0; b < 4; ++b)
      bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(file[10 + header_len + i * 4 + b])) << (8 * b);
    EXPECT_EQ(bits, std::bit_cast<std::uint32_t>(values[i])) << i;
  }
}

TEST(ImageIoNpy, LargeShapeAndErrors) {
  const std::filesystem::path dir = scratch_dir();
  const std::vector<float> values(static_cast<std::size_t>(1920) * 1080, 1.0f);
  write_npy(dir / "big.npy", 1920, 1080, values);
  const std::string file = read_bytes(dir / "big.npy");
  EXPECT_NE(file.find("'shape': (1080, 1920), }"), std::string::npos);
  EXPECT_EQ(file.size(), 128 + values.size() * 4);
  EXPECT_THROW(write_npy(dir / "short.npy", 3, 2, std::vector<float>(5)), std::invalid_argument);
  EXPECT_THROW(write_npy(dir / "missing" / "x.npy", 1, 1, std::vector<float>{0.5f}), std::runtime_error);
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"big.npy"});
}

// Animations: the container follows the extension, the bytes depend only on the frames, and bad input is refused
// before anything is written.
TEST(ImageIoAnimation, ContainersFollowTheExtension) {
  const std::filesystem::path dir = scratch_dir();
  std::vector<std::vector<std::uint8_t>> frames;
  for (unsigned k = 0; k < 5; ++k) frames.push_back(random_bytes(33 * 17 * 4, k));
  write_animation(dir / "a.mp4", 33, 17, frames, 0.1);
  write_animation(dir / "b.MP4", 33, 17, frames, 0.1);
  write_animation(dir / "c.webm", 33, 17, frames, 0.1);
  write_animation(dir / "d.gif", 33, 17, frames, 0.1);
  const std::string mp4 = read_bytes(dir / "a.mp4"), webm = read_bytes(dir / "c.webm"), gif = read_bytes(dir / "d.gif");
  ASSERT_GT(mp4.size(), 16u);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");                 // an ISO base media file
  EXPECT_EQ(webm.substr(0, 4), "\x1a\x45\xdf\xa3");     // EBML, as Matroska and WebM begin
  EXPECT_EQ(gif.substr(0, 6), "GIF89a");
  EXPECT_EQ(read_bytes(dir / "b.MP4"), mp4);           // the same frames, the same bytes
  EXPECT_TRUE(is_animation_path("x.WebM"));
  EXPECT_FALSE(is_animation_path("x.png"));

  EXPECT_THROW(write_animation(dir / "e.mkv", 33, 17, frames, 0.1), std::invalid_argument);
  EXPECT_THROW(write_animation(dir / "f.mp4", 32, 17, frames, 0.1), std::invalid_argument);  // wrong frame size
  EXPECT_THROW(write_animation(dir / "g.webm", 33, 17, {}, 0.1), std::invalid_argument);
  EXPECT_EQ(names_in(dir), (std::vector<std::string>{"a.mp4", "b.MP4", "c.webm", "d.gif"}));
}

}  // namespace
}  // namespace facet::image_io_tests
