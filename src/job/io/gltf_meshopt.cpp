// gltf_meshopt.cpp - glTF's EXT_meshopt_compression: compressed buffer views decoded with meshoptimizer into
// buffers of their own before any accessor is read.
#include <tiny_gltf.h>

// A build without meshoptimizer (the browser page's, FACET_NO_MESHOPT) refuses compressed views with that reason.
#ifndef FACET_NO_MESHOPT
#include <meshoptimizer.h>
#endif
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "job/io/gltf_meshopt.hpp"
#include "job/io/gltf_primitive.hpp"
#include "job/io/loaders.hpp"

namespace facet {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";
// What a placeholder buffer becomes for tinygltf: one byte, too short for any compressed view to read.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";
// No stream decodes to more than 64 times its size: the attribute codec spends at least 2 header bits on 16 bytes
// (a group of 16 elements' byte k), the triangle codec a byte on 3 indices, the index codec a byte on one.
constexpr std::uint64_t kMaxExpansion = 64;

enum class StreamMode { attributes, triangles, indices };
enum class StreamFilter { none, octahedral, quaternion, exponential };

bool is_placeholder(const tinygltf::Buffer& buffer) { return buffer.uri == kPlaceholderUri; }

// Refuses the file over one compressed buffer view's problem.
struct ViewError {
  const std::string& source;
  std::size_t view;
  [[noreturn]] void operator()(const std::string& problem) const {
    throw InputError(source, "bufferView " + std::to_string(view) + ": " + kExtension + ": " + problem);
  }
};

// The JSON with each placeholder buffer (and each fallback buffer, when this build decodes) given one byte of
// embedded data; nullopt when the file does not use the extension or has no such buffer (or the text does not
// parse: tinygltf then reports the problem).
std::optional<std::string> json_without_placeholders(std::string_view json, bool binary) {
  if (json.find(kExtension) == std::string_view::npos) return std::nullopt;
  nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
  if (document.is_discarded() || !document.is_object()) return std::nullopt;
  const auto used = document.find("extensionsUsed");
  if (used == document.end() || !used->is_array() ||
      std::none_of(used->begin(), used->end(), [](const nlohmann::json& e) { return e == kExtension; }))
    return std::nullopt;
  const auto buffers = document.find("buffers");
  if (buffers == document.end() || !buffers->is_array()) return std::nullopt;
  bool changed = false;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    nlohmann::json& buffer = (*buffers)[i];
    if (!buffer.is_object()) continue;
    const bool has_uri = buffer.contains("uri");
    bool fallback = false;
    if (const auto extensions = buffer.find("extensions"); extensions != buffer.end() && extensions->is_object())
      if (const auto ours = extensions->find(kExtension); ours != extensions->end() && ours->is_object())
        fallback = ours->contains("fallback") && (*ours)["fallback"] == true;
    const bool bin_chunk = binary && i == 0 && !has_uri;
    if ((has_uri || bin_chunk) && !(fallback && decodes_meshopt())) continue;
    buffer["uri"] = kPlaceholderUri;
    buffer["byteLength"] = 1;
    changed = true;
  }
  if (!changed) return std::nullopt;
  return document.dump();
}

// Which buffer views the meshes' accessors read (attributes, indices and sparse substitutions).
std::vector<bool> views_meshes_read(const tinygltf::Model& model) {
  std::vector<bool> read(model.bufferViews.size(), false);
  const auto view = [&](int index) {
    if (index >= 0 && static_cast<std::size_t>(index) < read.size()) read[static_cast<std::size_t>(index)] = true;
  };
  const auto accessor = [&](int index) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) return;
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    view(a.bufferView);
    if (a.sparse.isSparse) {
      view(a.sparse.indices.bufferView);
      view(a.sparse.values.bufferView);
    }
  };
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) {
      for (const auto& [name, index] : p.attributes) accessor(index);
      accessor(p.indices);
    }
  return read;
}

#ifndef FACET_NO_MESHOPT
// Decodes `count` elements of `stride` bytes into out; meshoptimizer's result (0 on success).
int decode_stream(StreamMode mode, StreamFilter filter, std::size_t count, std::size_t stride,
                  const unsigned char* data, std::size_t length, unsigned char* out) {
  int result = 0;
  switch (mode) {
    case StreamMode::attributes: result = meshopt_decodeVertexBuffer(out, count, stride, data, length); break;
    case StreamMode::triangles: result = meshopt_decodeIndexBuffer(out, count, stride, data, length); break;
    case StreamMode::indices: result = meshopt_decodeIndexSequence(out, count, stride, data, length); break;
  }
  if (result != 0) return result;
  switch (filter) {
    case StreamFilter::none: break;
    case StreamFilter::octahedral: meshopt_decodeFilterOct(out, count, stride); break;
    case StreamFilter::quaternion: meshopt_decodeFilterQuat(out, count, stride); break;
    case StreamFilter::exponential: meshopt_decodeFilterExp(out, count, stride); break;
  }
  return 0;
}
#else
int decode_stream(StreamMode, StreamFilter, std::size_t, std::size_t, const unsigned char*, std::size_t,
                  unsigned char*) {
  return -1;  // not reached: decode_meshopt refuses first
}
#endif

}  // namespace

bool decodes_meshopt() {
#ifdef FACET_NO_MESHOPT
  return false;
#else
  return true;
#endif
}

std::optional<std::string> without_meshopt_placeholders(std::string_view bytes, bool binary) {
  return with_gltf_json_rewritten(bytes, binary, &json_without_placeholders);
}

void decode_meshopt(tinygltf::Model& model, const std::string& source) {
  const std::size_t file_buffers = model.buffers.size();
  std::uint64_t held = 0;  // the bytes the file's buffers hold
  for (const tinygltf::Buffer& buffer : model.buffers)
    if (!is_placeholder(buffer)) held += buffer.data.size();
  // Every decoded byte comes from a compressed one, unless views share their compressed bytes; 1 GiB is what an
  // uncompressed file may hold.
  const std::uint64_t budget = std::min<std::uint64_t>(kMaxExpansion * held, kMaxModelFileBytes);
  std::uint64_t decoded = 0;
  const std::vector<bool> read = views_meshes_read(model);

  for (std::size_t v = 0; v < model.bufferViews.size(); ++v) {
    tinygltf::BufferView& view = model.bufferViews[v];
    const auto found = view.extensions.find(kExtension);
    if (found == view.extensions.end() || !read[v]) continue;
    const ViewError fail{source, v};
    if (!decodes_meshopt()) {
      // The view's own buffer may hold the uncompressed data (a fallback buffer with a uri).
      const bool own = view.buffer >= 0 && static_cast<std::size_t>(view.buffer) < file_buffers;
      const tinygltf::Buffer* buffer = own ? &model.buffers[static_cast<std::size_t>(view.buffer)] : nullptr;
      if (buffer && !is_placeholder(*buffer) && view.byteOffset <= buffer->data.size() &&
          view.byteLength <= buffer->data.size() - view.byteOffset)
        continue;
      throw InputError(source, "bufferView " + std::to_string(v) + ": this build cannot decode " + kExtension);
    }

    const tinygltf::Value& extension = found->second;
    if (!extension.IsObject()) fail("the extension has no buffer, byteLength, byteStride, count or mode");
    // A non-negative integer (tinygltf holds JSON integers as int: larger ones wrap, and are refused or checked
    // like any other value).
    const auto integer = [&](const char* key, bool required) -> std::uint64_t {
      if (!extension.Has(key)) {
        if (required) fail(std::string("it has no ") + key);
        return 0;
      }
      const tinygltf::Value& value = extension.Get(key);
      const double x = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
      if (!(x >= 0.0 && x <= 9007199254740992.0 && x == std::floor(x)))
        fail(std::string(key) + " is not a non-negative integer");
      return static_cast<std::uint64_t>(x);
    };
    const auto name = [&](const char* key, const char* fallback) -> std::string {
      if (!extension.Has(key)) {
        if (!fallback) fail(std::string("it has no ") + key);
        return fallback;
      }
      const tinygltf::Value& value = extension.Get(key);
      if (!value.IsString()) fail(std::string(key) + " is not a string");
      return value.Get<std::string>();
    };
    const std::uint64_t buffer_index = integer("buffer", true), offset = integer("byteOffset", false);
    const std::uint64_t length = integer("byteLength", true), stride = integer("byteStride", true);
    const std::uint64_t count = integer("count", true);
    const std::string mode_name = name("mode", nullptr), filter_name = name("filter", "NONE");

    StreamMode mode = StreamMode::attributes;
    if (mode_name == "TRIANGLES") mode = StreamMode::triangles;
    else if (mode_name == "INDICES") mode = StreamMode::indices;
    else if (mode_name != "ATTRIBUTES")
      fail("mode '" + printable(mode_name) + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    StreamFilter filter = StreamFilter::none;
    if (filter_name == "OCTAHEDRAL") filter = StreamFilter::octahedral;
    else if (filter_name == "QUATERNION") filter = StreamFilter::quaternion;
    else if (filter_name == "EXPONENTIAL") filter = StreamFilter::exponential;
    else if (filter_name != "NONE")
      fail("filter '" + printable(filter_name) + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");

    // The specification's rules, which are also what meshoptimizer's decoders assert.
    const std::string strided = "byteStride " + std::to_string(stride);
    if (mode == StreamMode::attributes) {
      if (stride == 0 || stride % 4 != 0 || stride > 256)
        fail(strided + " is not a multiple of 4 from 4 to 256, as ATTRIBUTES needs");
    } else {
      if (stride != 2 && stride != 4) fail(strided + " is not 2 or 4, as " + mode_name + " needs");
      if (filter != StreamFilter::none) fail(mode_name + " takes no filter, not " + filter_name);
      if (mode == StreamMode::triangles && count % 3 != 0)
        fail("count " + std::to_string(count) + " is not a multiple of 3, as TRIANGLES needs");
    }
    if (filter == StreamFilter::octahedral && stride != 4 && stride != 8)
      fail(strided + " is not 4 or 8, as OCTAHEDRAL needs");
    if (filter == StreamFilter::quaternion && stride != 8) fail(strided + " is not 8, as QUATERNION needs");
    if (view.byteStride != 0 && view.byteStride != stride)
      fail(strided + " differs from the buffer view's " + std::to_string(view.byteStride));

    if (buffer_index >= file_buffers) fail("buffer " + std::to_string(buffer_index) + " does not exist");
    const tinygltf::Buffer& compressed = model.buffers[buffer_index];
    if (is_placeholder(compressed))
      fail("buffer " + std::to_string(buffer_index) + " is a placeholder that holds no data");
    if (offset > compressed.data.size() || length > compressed.data.size() - offset)
      fail("byteOffset " + std::to_string(offset) + " and byteLength " + std::to_string(length) +
           " reach past the end of buffer " + std::to_string(buffer_index) + " (" +
           std::to_string(compressed.data.size()) + " bytes)");

    // count < 2^53 and stride <= 256, so the product cannot wrap.
    const std::uint64_t bytes = count * stride;
    const std::string size =
        "count " + std::to_string(count) + " * " + strided + " = " + std::to_string(bytes) + " bytes";
    if (bytes != view.byteLength)
      fail(size + ", but the buffer view's byteLength is " + std::to_string(view.byteLength));
    if (bytes > kMaxExpansion * length)
      fail(size + ", more than 64 times its " + std::to_string(length) + " compressed bytes");
    if (bytes > budget - decoded)
      fail(size + ", which takes the decoded buffer views past " + std::to_string(budget) +
           " bytes (64 times the file's buffers, at most 1 GiB)");
    decoded += bytes;

    std::vector<unsigned char> out(static_cast<std::size_t>(bytes));
    const int result = decode_stream(mode, filter, static_cast<std::size_t>(count), static_cast<std::size_t>(stride),
                                     compressed.data.data() + offset, static_cast<std::size_t>(length), out.data());
    if (result != 0)
      fail("the " + std::to_string(length) + " compressed bytes are not a valid " + mode_name + " stream of " +
           std::to_string(count) + " elements (meshoptimizer's error " + std::to_string(result) + ")");

    // `compressed` is not used past here: appending may move the buffers.
    tinygltf::Buffer decoded_buffer;
    decoded_buffer.name = std::string(kExtension) + " of bufferView " + std::to_string(v);
    decoded_buffer.data = std::move(out);
    model.buffers.push_back(std::move(decoded_buffer));
    view.buffer = static_cast<int>(model.buffers.size() - 1);
    view.byteOffset = 0;
  }
}

}  // namespace facet
