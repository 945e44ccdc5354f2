// video.cpp - frames to an MP4 or WebM file in memory: swscale to YUV 4:2:0, libavcodec, libavformat.
#include "job/io/video.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "job/shared_library.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace facet {

namespace {

// FFmpeg's functions facet calls, with the library of each. FFmpeg is opened on the first video written, not
// linked: its libraries bring in over a hundred more, which would slow the start of every facet process.
// clang-format off
#define FACET_FFMPEG_FUNCTIONS(X) \
  X(avutil, av_d2q) X(avutil, av_frame_alloc) X(avutil, av_frame_free) X(avutil, av_frame_get_buffer) \
  X(avutil, av_frame_make_writable) X(avutil, av_free) X(avutil, av_freep) X(avutil, av_log_get_level) \
  X(avutil, av_log_set_level) X(avutil, av_malloc) X(avutil, av_opt_set) X(avutil, av_strerror) \
  X(avcodec, av_packet_alloc) X(avcodec, av_packet_free) X(avcodec, av_packet_rescale_ts) \
  X(avcodec, avcodec_alloc_context3) X(avcodec, avcodec_find_encoder) \
  X(avcodec, avcodec_find_encoder_by_name) X(avcodec, avcodec_free_context) X(avcodec, avcodec_open2) \
  X(avcodec, avcodec_parameters_from_context) X(avcodec, avcodec_receive_packet) \
  X(avcodec, avcodec_send_frame) \
  X(avformat, av_guess_format) X(avformat, av_interleaved_write_frame) X(avformat, av_write_trailer) \
  X(avformat, avformat_alloc_context) X(avformat, avformat_free_context) X(avformat, avformat_new_stream) \
  X(avformat, avformat_write_header) X(avformat, avio_alloc_context) X(avformat, avio_context_free) \
  X(avformat, avio_flush) \
  X(swscale, sws_getContext) X(swscale, sws_freeContext) X(swscale, sws_setColorspaceDetails) \
  X(swscale, sws_getCoefficients) X(swscale, sws_scale)
// clang-format on

struct Ffmpeg {
#define FACET_DECLARE(library, name) decltype(&::name) name = nullptr;
  FACET_FFMPEG_FUNCTIONS(FACET_DECLARE)
#undef FACET_DECLARE
};

// The table, filled on first use from the sonames of the FFmpeg headers facet was built with (libavcodec.so.59 for
// FFmpeg 5.1). Throws std::runtime_error naming the missing library and its package; a later call tries again.
const Ffmpeg& ffmpeg() {
  static const Ffmpeg table = [] {
    const SharedLibrary avutil("libavutil.so." AV_STRINGIFY(LIBAVUTIL_VERSION_MAJOR),
                               "libavutil" AV_STRINGIFY(LIBAVUTIL_VERSION_MAJOR));
    const SharedLibrary avcodec("libavcodec.so." AV_STRINGIFY(LIBAVCODEC_VERSION_MAJOR),
                                "libavcodec" AV_STRINGIFY(LIBAVCODEC_VERSION_MAJOR));
    const SharedLibrary avformat("libavformat.so." AV_STRINGIFY(LIBAVFORMAT_VERSION_MAJOR),
                                 "libavformat" AV_STRINGIFY(LIBAVFORMAT_VERSION_MAJOR));
    const SharedLibrary swscale("libswscale.so." AV_STRINGIFY(LIBSWSCALE_VERSION_MAJOR),
                                "libswscale" AV_STRINGIFY(LIBSWSCALE_VERSION_MAJOR));
    Ffmpeg f;
#define FACET_RESOLVE(library, name) f.name = library.function<decltype(&::name)>(#name);
    FACET_FFMPEG_FUNCTIONS(FACET_RESOLVE)
#undef FACET_RESOLVE
    // FFmpeg reports progress on stderr by default; facet reports its errors in exceptions. A level an application
    // has chosen is left alone.
    if (f.av_log_get_level() == AV_LOG_INFO) f.av_log_set_level(AV_LOG_QUIET);
    return f;
  }();
  return table;
}

[[noreturn]] void failed(const std::string& what, int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  ffmpeg().av_strerror(code, text, sizeof text);
  throw std::runtime_error("video encoding: " + what + ": " + text);
}

void check(int code, const std::string& what) {
  if (code < 0) failed(what, code);
}

// The muxer writes into a growing byte vector and seeks back in it (MP4 patches sizes into its header at the end),
// so the file is whole in memory before write_output puts it anywhere, a pipe included.
struct MemoryFile {
  std::vector<std::uint8_t> bytes;
  std::size_t position = 0;

  static int write(void* opaque, std::uint8_t* data, int size) {
    auto* file = static_cast<MemoryFile*>(opaque);
    const std::size_t end = file->position + static_cast<std::size_t>(size);
    if (end > file->bytes.size()) file->bytes.resize(end);
    std::memcpy(file->bytes.data() + file->position, data, static_cast<std::size_t>(size));
    file->position = end;
    return size;
  }

  static std::int64_t seek(void* opaque, std::int64_t offset, int whence) {
    auto* file = static_cast<MemoryFile*>(opaque);
    const auto size = static_cast<std::int64_t>(file->bytes.size());
    if (whence & AVSEEK_SIZE) return size;
    std::int64_t base = 0;
    switch (whence & ~AVSEEK_FORCE) {
      case SEEK_SET: base = 0; break;
      case SEEK_CUR: base = static_cast<std::int64_t>(file->position); break;
      case SEEK_END: base = size; break;
      default: return AVERROR(EINVAL);
    }
    if (base + offset < 0) return AVERROR(EINVAL);
    file->position = static_cast<std::size_t>(base + offset);
    return base + offset;
  }
};

struct CodecContextFree {
  void operator()(AVCodecContext* c) const { ffmpeg().avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { ffmpeg().av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { ffmpeg().av_packet_free(&p); }
};
struct FormatFree {
  void operator()(AVFormatContext* f) const { ffmpeg().avformat_free_context(f); }
};
struct IoFree {
  void operator()(AVIOContext* io) const {
    ffmpeg().av_freep(&io->buffer);
    ffmpeg().avio_context_free(&io);
  }
};
struct ScaleFree {
  void operator()(SwsContext* s) const { ffmpeg().sws_freeContext(s); }
};

// The encoder for the container: H.264 (x264 first) in MP4, VP9 (else VP8) in WebM, with settings for sharp
// renders at small sizes; one thread, so the stream is the same on any machine load. x264's "veryfast" preset at
// CRF 18: on a 640x480 clip it encodes in two thirds of "medium"'s time, to a file no larger (renders are flat,
// smooth images, where the slower presets' extra search finds little).
std::unique_ptr<AVCodecContext, CodecContextFree> open_encoder(VideoFormat format, int width, int height,
                                                               AVRational time_base, bool global_header) {
  const Ffmpeg& ff = ffmpeg();
  const char* const names[2][2] = {{"libx264", nullptr}, {"libvpx-vp9", "libvpx"}};
  const AVCodec* codec = nullptr;
  for (const char* name : names[format == VideoFormat::webm ? 1 : 0])
    if (name && !codec) codec = ff.avcodec_find_encoder_by_name(name);
  if (!codec && format == VideoFormat::mp4) codec = ff.avcodec_find_encoder(AV_CODEC_ID_H264);
  if (!codec)
    throw std::runtime_error(std::string("video encoding: this FFmpeg has no ") +
                             (format == VideoFormat::mp4 ? "H.264" : "VP9 or VP8") + " encoder");
  std::unique_ptr<AVCodecContext, CodecContextFree> context(ff.avcodec_alloc_context3(codec));
  if (!context) throw std::bad_alloc();
  AVCodecContext& c = *context;
  c.width = width;
  c.height = height;
  c.pix_fmt = AV_PIX_FMT_YUV420P;
  c.time_base = time_base;
  c.framerate = av_inv_q(time_base);
  c.gop_size = 60;
  c.thread_count = 1;
  c.color_range = AVCOL_RANGE_MPEG;
  c.colorspace = AVCOL_SPC_BT709;
  c.color_primaries = AVCOL_PRI_BT709;
  c.color_trc = AVCOL_TRC_IEC61966_2_1;
  c.flags |= AV_CODEC_FLAG_BITEXACT;
  if (global_header) c.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (format == VideoFormat::mp4) {
    ff.av_opt_set(c.priv_data, "preset", "veryfast", 0);
    ff.av_opt_set(c.priv_data, "crf", "18", 0);
  } else {
    c.bit_rate = 0;  // constant quality
    ff.av_opt_set(c.priv_data, "crf", "30", 0);
    ff.av_opt_set(c.priv_data, "deadline", "good", 0);
    ff.av_opt_set(c.priv_data, "cpu-used", "4", 0);
    ff.av_opt_set(c.priv_data, "row-mt", "0", 0);
  }
  check(ff.avcodec_open2(context.get(), codec, nullptr), std::string("cannot open ") + codec->name);
  return context;
}

// An RGBA frame grown to even_width x even_height by repeating its last column and row.
std::vector<std::uint8_t> pad_to(std::span<const std::uint8_t> rgba, int width, int height, int even_width,
                                 int even_height) {
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(even_width) * even_height * 4);
  for (int y = 0; y < even_height; ++y) {
    const std::uint8_t* source = rgba.data() + static_cast<std::size_t>(std::min(y, height - 1)) * width * 4;
    std::uint8_t* row = padded.data() + static_cast<std::size_t>(y) * even_width * 4;
    std::memcpy(row, source, static_cast<std::size_t>(width) * 4);
    if (even_width > width) std::memcpy(row + static_cast<std::size_t>(width) * 4, row + (width - 1) * 4, 4);
  }
  return padded;
}

}  // namespace

std::vector<std::uint8_t> encode_video(VideoFormat format, int width, int height,
                                       std::span<const std::vector<std::uint8_t>> frames, double frame_seconds) {
  if (frames.empty()) throw std::invalid_argument("video encoding: no frames");
  if (width <= 0 || height <= 0) throw std::invalid_argument("video encoding: bad size");
  const std::size_t frame_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
  for (const std::vector<std::uint8_t>& frame : frames)
    if (frame.size() != frame_bytes) throw std::invalid_argument("video encoding: a frame of the wrong size");
  if (!(frame_seconds > 0.0)) throw std::invalid_argument("video encoding: frame time must be positive");
  const Ffmpeg& ff = ffmpeg();
  const int even_width = width + (width & 1), even_height = height + (height & 1);
  const AVRational time_base = ff.av_d2q(frame_seconds, 100000);

  std::unique_ptr<AVFormatContext, FormatFree> muxer(ff.avformat_alloc_context());
  if (!muxer) throw std::bad_alloc();
  muxer->oformat = ff.av_guess_format(format == VideoFormat::mp4 ? "mp4" : "webm", nullptr, nullptr);
  if (!muxer->oformat) throw std::runtime_error("video encoding: this FFmpeg has no muxer for the container");
  MemoryFile file;
  constexpr int kIoBuffer = 1 << 16;
  auto* io_buffer = static_cast<unsigned char*>(ff.av_malloc(kIoBuffer));
  if (!io_buffer) throw std::bad_alloc();
  std::unique_ptr<AVIOContext, IoFree> io(
      ff.avio_alloc_context(io_buffer, kIoBuffer, 1, &file, nullptr, &MemoryFile::write, &MemoryFile::seek));
  if (!io) {
    ff.av_free(io_buffer);
    throw std::bad_alloc();
  }
  muxer->pb = io.get();
  muxer->flags |= AVFMT_FLAG_CUSTOM_IO | AVFMT_FLAG_BITEXACT;

  auto encoder =
      open_encoder(format, even_width, even_height, time_base, (muxer->oformat->flags & AVFMT_GLOBALHEADER) != 0);
  AVStream* stream = ff.avformat_new_stream(muxer.get(), nullptr);
  if (!stream) throw std::bad_alloc();
  stream->time_base = time_base;
  check(ff.avcodec_parameters_from_context(stream->codecpar, encoder.get()), "stream parameters");
  check(ff.avformat_write_header(muxer.get(), nullptr), "container header");

  std::unique_ptr<SwsContext, ScaleFree> scale(
      ff.sws_getContext(even_width, even_height, AV_PIX_FMT_RGBA, even_width, even_height, AV_PIX_FMT_YUV420P,
                        SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr));
  if (!scale) throw std::runtime_error("video encoding: no RGBA to YUV 4:2:0 conversion");
  // sRGB values stored as BT.709 YUV in limited range, the combination players assume for HD video.
  ff.sws_setColorspaceDetails(scale.get(), ff.sws_getCoefficients(SWS_CS_ITU709), 1,
                              ff.sws_getCoefficients(SWS_CS_ITU709), 0, 0, 1 << 16, 1 << 16);
  std::unique_ptr<AVFrame, FrameFree> picture(ff.av_frame_alloc());
  std::unique_ptr<AVPacket, PacketFree> packet(ff.av_packet_alloc());
  if (!picture || !packet) throw std::bad_alloc();
  picture->format = AV_PIX_FMT_YUV420P;
  picture->width = even_width;
  picture->height = even_height;
  check(ff.av_frame_get_buffer(picture.get(), 0), "frame buffer");

  // Sends one frame (or, with none, the end of the stream) and muxes every packet the encoder has ready.
  auto encode = [&](const AVFrame* input) {
    check(ff.avcodec_send_frame(encoder.get(), input), "encoding a frame");
    for (;;) {
      const int got = ff.avcodec_receive_packet(encoder.get(), packet.get());
      if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
      check(got, "encoding a frame");
      ff.av_packet_rescale_ts(packet.get(), encoder->time_base, stream->time_base);
      packet->stream_index = stream->index;
      check(ff.av_interleaved_write_frame(muxer.get(), packet.get()), "writing a frame");
    }
  };
  const bool padded = even_width != width || even_height != height;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    check(ff.av_frame_make_writable(picture.get()), "frame buffer");
    std::vector<std::uint8_t> grown;
    if (padded) grown = pad_to(frames[k], width, height, even_width, even_height);
    const std::uint8_t* source[1] = {padded ? grown.data() : frames[k].data()};
    const int source_stride[1] = {even_width * 4};
    ff.sws_scale(scale.get(), source, source_stride, 0, even_height, picture->data, picture->linesize);
    picture->pts = static_cast<std::int64_t>(k);
    encode(picture.get());
  }
  encode(nullptr);
  check(ff.av_write_trailer(muxer.get()), "container trailer");
  ff.avio_flush(io.get());
  return std::move(file.bytes);
}

}  // namespace facet
