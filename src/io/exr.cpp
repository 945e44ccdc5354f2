// exr.cpp - OpenEXR encoding through the OpenEXR library, into memory so the caller can write atomically.
#include "io/exr.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>

namespace facet {
namespace {

// OpenEXR writes through an OStream; this one appends to a byte vector and can seek back (the line offset table
// is written last).
class MemoryStream final : public Imf::OStream {
 public:
  explicit MemoryStream(std::vector<std::uint8_t>& bytes) : Imf::OStream("memory"), bytes_(bytes) {}
  void write(const char c[], int n) override {
    const auto count = static_cast<std::size_t>(n);
    if (position_ + count > bytes_.size()) bytes_.resize(position_ + count);
    std::memcpy(bytes_.data() + position_, c, count);
    position_ += count;
  }
  std::uint64_t tellp() override { return position_; }
  void seekp(std::uint64_t pos) override { position_ = static_cast<std::size_t>(pos); }

 private:
  std::vector<std::uint8_t>& bytes_;
  std::size_t position_ = 0;
};

}  // namespace

std::vector<std::uint8_t> encode_exr(int width, int height, int channels, std::span<const float> values) {
  static constexpr const char* kGray[] = {"Y"};
  static constexpr const char* kRgb[] = {"R", "G", "B"};
  if (channels != 1 && channels != 3)
    throw std::invalid_argument("EXR: 1 or 3 channels, not " + std::to_string(channels));
  const char* const* names = channels == 1 ? kGray : kRgb;
  std::vector<std::uint8_t> bytes;
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const std::size_t pixel_bytes = sizeof(float) * static_cast<std::size_t>(channels);
    for (int c = 0; c < channels; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      // OpenEXR reads through a non-const pointer but does not write when saving.
      char* base = reinterpret_cast<char*>(const_cast<float*>(values.data() + c));
      frame.insert(names[c], Imf::Slice(Imf::FLOAT, base, pixel_bytes, pixel_bytes * static_cast<std::size_t>(width)));
    }
    MemoryStream stream(bytes);
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("OpenEXR: ") + e.what());
  }
  return bytes;
}

}  // namespace facet
