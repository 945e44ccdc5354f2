// png.cpp - the PNG encoder: signature, IHDR, one IDAT of Up-filtered rows deflated by ISA-L in bands, IEND.
#include "job/io/png.hpp"

#include <isa-l/igzip_lib.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

namespace facet {
namespace {

// A part of the image takes this many rows of pixel data at least: splitting smaller images costs more in threads
// and flushes than it saves.
constexpr std::size_t kMinPartBytes = std::size_t{1} << 20;
constexpr int kMaxParts = 8;
constexpr int kRowsPerStep = 16;  // rows filtered at a time, into a buffer that stays in cache

void store_u32(std::uint8_t* out, std::uint32_t v) {  // PNG integers are big-endian
  out[0] = static_cast<std::uint8_t>(v >> 24);
  out[1] = static_cast<std::uint8_t>(v >> 16);
  out[2] = static_cast<std::uint8_t>(v >> 8);
  out[3] = static_cast<std::uint8_t>(v);
}

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.resize(out.size() + 4);
  store_u32(out.data() + out.size() - 4, v);
}

// A chunk: length, type, data, and the CRC of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char* type, std::span<const std::uint8_t> data) {
  put_u32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.resize(start + 4 + data.size());
  std::memcpy(out.data() + start, type, 4);
  if (!data.empty()) std::memcpy(out.data() + start + 4, data.data(), data.size());
  put_u32(out, static_cast<std::uint32_t>(
                   crc32(0, out.data() + start, static_cast<uInt>(out.size() - start))));
}

// PNG's rules for tEXt: a keyword of 1-79 printable Latin-1 characters, no leading, trailing or double spaces,
// and text without NUL.
void check_text(const PngText& chunk) {
  const std::string& k = chunk.keyword;
  bool ok = !k.empty() && k.size() <= 79 && k.front() != ' ' && k.back() != ' ' && k.find("  ") == std::string::npos;
  for (const char c : k) {
    const auto u = static_cast<unsigned char>(c);
    ok = ok && ((u >= 32 && u <= 126) || u >= 161);
  }
  if (!ok) throw std::invalid_argument("PNG: bad text keyword '" + k + "'");
  if (chunk.text.find('\0') != std::string::npos)
    throw std::invalid_argument("PNG: the text of '" + k + "' holds a NUL byte");
}

// The image's rows as the encoder reads them.
struct Rows {
  const std::uint8_t* pixels;
  std::size_t width, channels, source_channels;
  std::size_t bytes() const { return width * channels; }  // per row in the file, without the filter byte
};

// The eight byte differences a[i] - b[i] (mod 256) of two 8-byte words at once, no borrow crossing a byte: each byte
// of a with its top bit set minus each of b with it clear cannot borrow, and the top bits are then put right.
std::uint64_t byte_differences(std::uint64_t a, std::uint64_t b) {
  constexpr std::uint64_t kTop = 0x8080808080808080u;
  return ((a | kTop) - (b & ~kTop)) ^ ((a ^ ~b) & kTop);
}

std::uint64_t load_u64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Row y with the Up filter (type 2: the difference from the row above; the first row's "row above" is zero), its
// filter byte first, in out[0 .. bytes()]. Samples of the source beyond `channels` are dropped. Eight bytes at a
// time: the filter is a fifth of a 1920x1080 render's PNG time byte by byte (WusonOBJ), where zlib's run-length
// pass is the rest.
void filter_row(const Rows& rows, std::size_t y, std::uint8_t* out) {
  const std::size_t n = rows.channels, m = rows.source_channels, source_row = rows.width * m;
  const std::uint8_t* line = rows.pixels + y * source_row;
  const std::uint8_t* above = y == 0 ? nullptr : line - source_row;
  out[0] = 2;
  ++out;
  if (above && n == m) {
    std::size_t i = 0;
    for (; i + 8 <= rows.bytes(); i += 8) {
      const std::uint64_t d = byte_differences(load_u64(line + i), load_u64(above + i));
      std::memcpy(out + i, &d, sizeof d);
    }
    for (; i < rows.bytes(); ++i) out[i] = static_cast<std::uint8_t>(line[i] - above[i]);
    return;
  }
  std::size_t x = 0;  // pixels done
  if (above && n == 3 && m == 4) {
    // Two RGBA pixels a word; their six colour bytes are stored as eight, the last two rewritten by the next pair
    // (so the loop leaves at least one pixel to the end).
    for (; x + 3 <= rows.width; x += 2) {
      const std::uint64_t d = byte_differences(load_u64(line + x * 4), load_u64(above + x * 4));
      const std::uint64_t rgb = (d & 0xffffffu) | (d >> 8 & 0xffffff000000u);
      std::memcpy(out + x * 3, &rgb, sizeof rgb);
    }
  }
  for (; x < rows.width; ++x)
    for (std::size_t c = 0; c < n; ++c)
      out[x * n + c] = static_cast<std::uint8_t>(line[x * m + c] - (above ? above[x * m + c] : 0));
}

// Rows [first, last) filtered and compressed as raw deflate, with their Adler-32 (of the filtered bytes): a part that
// is not the last ends with a sync flush (an empty stored block, byte-aligned, not final), so the parts of an image
// concatenate into one deflate stream. ISA-L's level 1 (igzip), not zlib: on 1920x1080 renders it deflates the
// filtered rows in a ninth of zlib's fastest time (Z_RLE at level 1), and its Adler-32 takes a third of zlib's, for
// files 3-40% larger (docs/PERFORMANCE.md, "Other measures").
struct DeflatedPart {
  std::vector<std::uint8_t> bytes;
  std::uint32_t adler = 1;
  std::size_t length = 0;  // filtered bytes
  std::string error;
};

constexpr std::uint32_t kPrimeBytes = 16;  // ISA-L's MIN_INBUF_PADDING: a flushed call this short skips its loop

// Deflates z's input into part.bytes from `written` on, until the input is taken and (with a state to reach, at
// the end of a band or of the stream's first bytes) the stream is in that state; false on failure.
bool deflate_all(isal_zstream& z, DeflatedPart& part, std::size_t& written, std::optional<int> until) {
  for (;;) {
    if (part.bytes.size() - written < 1024) part.bytes.resize(part.bytes.size() * 2);
    z.next_out = part.bytes.data() + written;
    z.avail_out = static_cast<std::uint32_t>(part.bytes.size() - written);
    if (isal_deflate(&z) != COMP_OK) {
      part.error = "PNG: compression failed";
      return false;
    }
    written = part.bytes.size() - z.avail_out;
    if (z.avail_in != 0 || z.avail_out == 0) continue;
    if (!until || static_cast<int>(z.internal_state.state) == *until) return true;
  }
}

void deflate_rows(const Rows& rows, std::size_t first, std::size_t last, bool final_part, DeflatedPart& part) {
  // The stream keeps its 32 KiB history inside itself: 80 KB, too much for a helper thread's stack.
  const auto stream = std::make_unique<isal_zstream>();
  isal_zstream& z = *stream;
  isal_deflate_init(&z);
  std::vector<std::uint8_t> level_buffer(ISAL_DEF_LVL1_SMALL);
  z.level = 1;
  z.level_buf = level_buffer.data();
  z.level_buf_size = static_cast<std::uint32_t>(level_buffer.size());
  z.gzip_flag = IGZIP_DEFLATE;
  const std::size_t stride = rows.bytes() + 1;
  std::vector<std::uint8_t> filtered(stride * kRowsPerStep);
  part.bytes.resize(std::max<std::size_t>(4096, (last - first) * stride / 32));
  std::size_t written = 0;
  std::uint32_t adler = 1;
  for (std::size_t y = first; y < last; y += kRowsPerStep) {
    const std::size_t count = std::min<std::size_t>(kRowsPerStep, last - y);
    for (std::size_t k = 0; k < count; ++k) filter_row(rows, y + k, filtered.data() + k * stride);
    const auto in = static_cast<std::uint32_t>(count * stride);
    adler = isal_adler32(adler, filtered.data(), in);
    part.length += in;
    // ISA-L's level-1 assembly (igzip_icf_body_h1_gr_bt.asm, .write_first_byte; 2.30 to 2.32 at least) hashes a
    // register it never loaded, which holds the isal_zstream's address, for a new stream's third byte: the hash
    // table then depends on where the stream was allocated, and about one image in 400 deflates to other (valid)
    // bytes from one run to another. A stream's first bytes are therefore deflated alone with a sync flush (which
    // keeps the history): 16 bytes or fewer with a flush skip that loop for ISA-L's finishing code, which hashes
    // them right, and the loop then never sees a stream without history.
    std::uint32_t primed = 0;
    if (y == first && in > kPrimeBytes) {
      primed = kPrimeBytes;
      z.next_in = filtered.data();
      z.avail_in = primed;
      z.end_of_stream = 0;
      z.flush = SYNC_FLUSH;
      if (!deflate_all(z, part, written, ZSTATE_NEW_HDR)) return;
    }
    z.next_in = filtered.data() + primed;
    z.avail_in = in - primed;
    const bool end = y + count == last;
    z.end_of_stream = end && final_part;
    z.flush = end && !final_part ? SYNC_FLUSH : NO_FLUSH;
    if (!deflate_all(z, part, written, !end ? std::optional<int>() : final_part ? ZSTATE_END : ZSTATE_NEW_HDR))
      return;
  }
  part.bytes.resize(written);
  part.adler = adler;
}

}  // namespace

std::vector<std::uint8_t> encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels,
                                     int source_channels, int threads, std::span<const PngText> text) {
  for (const PngText& chunk : text) check_text(chunk);
  if (source_channels == 0) source_channels = channels;
  if (width < 1 || height < 1 || (channels != 1 && channels != 3 && channels != 4) || source_channels < channels ||
      source_channels > 4)
    throw std::invalid_argument("PNG: bad size " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                                std::to_string(channels));
  const Rows rows{pixels.data(), static_cast<std::size_t>(width), static_cast<std::size_t>(channels),
                  static_cast<std::size_t>(source_channels)};
  const auto h = static_cast<std::size_t>(height);
  if (pixels.size() != rows.width * rows.source_channels * h)
    throw std::invalid_argument("PNG: " + std::to_string(pixels.size()) + " bytes for " + std::to_string(width) + "x" +
                                std::to_string(height) + "x" + std::to_string(channels));

  // Bands of rows, one per thread, compressed at once; the caller's thread takes the first.
  const std::size_t by_size = std::max<std::size_t>(1, (rows.bytes() + 1) * h / kMinPartBytes);
  const auto most = static_cast<std::size_t>(std::clamp(threads, 1, kMaxParts));
  const int parts = static_cast<int>(std::min<std::size_t>({by_size, h, most}));
  std::vector<DeflatedPart> deflated(static_cast<std::size_t>(parts));
  const auto band = [&](int p) {
    const std::size_t first = h * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts);
    const std::size_t last = h * static_cast<std::size_t>(p + 1) / static_cast<std::size_t>(parts);
    deflate_rows(rows, first, last, p + 1 == parts, deflated[static_cast<std::size_t>(p)]);
  };
  {
    std::vector<std::jthread> helpers;
    for (int p = 1; p < parts; ++p) helpers.emplace_back(band, p);
    band(0);
  }
  // One zlib stream: its header (deflate, 32 KiB window, fastest), the parts, the Adler-32 of all filtered bytes.
  std::vector<std::uint8_t> zlib{0x78, 0x01};
  uLong adler = 1;
  for (const DeflatedPart& part : deflated) {
    if (!part.error.empty()) throw std::runtime_error(part.error);
    zlib.insert(zlib.end(), part.bytes.begin(), part.bytes.end());
    adler = adler32_combine(adler, part.adler, static_cast<z_off_t>(part.length));
  }
  put_u32(zlib, static_cast<std::uint32_t>(adler));

  std::vector<std::uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  png.reserve(zlib.size() + 64);
  // Size, then bit depth 8, the colour type (grey, RGB, RGBA), deflate, adaptive filtering, no interlacing.
  std::array<std::uint8_t, 13> header{0, 0, 0, 0, 0, 0, 0, 0, 8, 0, 0, 0, 0};
  store_u32(header.data(), static_cast<std::uint32_t>(width));
  store_u32(header.data() + 4, static_cast<std::uint32_t>(height));
  header[9] = channels == 1 ? 0 : channels == 3 ? 2 : 6;
  put_chunk(png, "IHDR", header);
  for (const PngText& chunk : text) {
    std::vector<std::uint8_t> data(chunk.keyword.begin(), chunk.keyword.end());
    data.push_back(0);  // the keyword's terminator
    data.insert(data.end(), chunk.text.begin(), chunk.text.end());
    put_chunk(png, "tEXt", data);
  }
  put_chunk(png, "IDAT", zlib);
  put_chunk(png, "IEND", {});
  return png;
}

}  // namespace facet
