// gltf_accessors.hpp - a glTF file's accessors read as checked arrays: every byte range inside its buffer.
#pragma once

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model.hpp"

namespace facet {

// The accessors of one loaded file, and the source name its errors carry.
struct Reader {
  const tinygltf::Model& model;
  const std::string& source;

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(source, problem); }

  // The accessor's elements as floats, `components` per element (normalized integers scaled to 0..1 or -1..1),
  // sparse substitutions applied. Every byte range is checked against its buffer.
  std::vector<float> floats(int index, int components, const char* what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) != components)
      fail(std::string(what) + ": accessor " + std::to_string(index) + " has the wrong type for this attribute");
    // Checked before anything is allocated: a count the buffer cannot hold (or, for an accessor of sparse values
    // alone, more vertices than any model may have) would otherwise claim gigabytes.
    const bool dense = a.bufferView >= 0;
    const Span span = dense ? elements(a, components, what) : Span{nullptr, 0};
    if (a.count > kMaxModelVertices)
      fail(std::string(what) + ": accessor " + std::to_string(index) + " has " + std::to_string(a.count) +
           " elements, more than 2^27");
    std::vector<float> out(a.count * static_cast<std::size_t>(components), 0.0f);
    if (dense) {
      for (std::size_t i = 0; i < a.count; ++i)
        for (int c = 0; c < components; ++c)
          out[i * components + c] = component(span.data + i * span.stride, a.componentType, c, a.normalized);
    }
    if (a.sparse.isSparse) {
      const std::vector<std::uint32_t> targets = sparse_indices(a, what);
      tinygltf::Accessor values = a;
      values.bufferView = a.sparse.values.bufferView;
      values.byteOffset = static_cast<std::size_t>(a.sparse.values.byteOffset);
      values.count = targets.size();
      const Span span = elements(values, components, what);
      for (std::size_t k = 0; k < targets.size(); ++k)
        for (int c = 0; c < components; ++c)
          out[targets[k] * components + c] = component(span.data + k * span.stride, a.componentType, c, a.normalized);
    }
    return out;
  }

  std::vector<std::uint32_t> indices(int index) const {
    const tinygltf::Accessor& a = accessor(index, "indices");
    if (a.type != TINYGLTF_TYPE_SCALAR || a.sparse.isSparse || a.bufferView < 0)
      fail("indices: accessor " + std::to_string(index) + " is not a plain scalar index list");
    const Span span = elements(a, 1, "indices");
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) out[i] = integer(span.data + i * span.stride, a.componentType, "indices");
    return out;
  }

  // The accessor's unsigned integer elements, `components` per element (JOINTS_n): dense, no sparse substitutions.
  std::vector<std::uint32_t> unsigned_integers(int index, int components, const char* what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type)) != components || a.normalized ||
        a.sparse.isSparse || a.bufferView < 0)
      fail(std::string(what) + ": accessor " + std::to_string(index) + " is not a plain list of unsigned integers");
    if (a.count > kMaxModelVertices)
      fail(std::string(what) + ": accessor " + std::to_string(index) + " has " + std::to_string(a.count) +
           " elements, more than 2^27");
    const Span span = elements(a, components, what);
    const auto size =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
    std::vector<std::uint32_t> out(a.count * static_cast<std::size_t>(components));
    for (std::size_t i = 0; i < a.count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * components + c] = integer(span.data + i * span.stride + size * c, a.componentType, what);
    return out;
  }

 private:
  struct Span {
    const unsigned char* data;
    std::size_t stride;
  };

  const tinygltf::Accessor& accessor(int index, const char* what) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
      fail(std::string(what) + ": accessor " + std::to_string(index) + " does not exist");
    return model.accessors[static_cast<std::size_t>(index)];
  }

  Span elements(const tinygltf::Accessor& a, int components, const char* what) const {
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    if (size <= 0) fail(std::string(what) + ": unknown component type " + std::to_string(a.componentType));
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
      fail(std::string(what) + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
      fail(std::string(what) + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
    const std::size_t element = static_cast<std::size_t>(size) * static_cast<std::size_t>(components);
    const std::size_t stride = view.byteStride ? view.byteStride : element;
    // Sizes come from the file: each sum is checked before it is formed, so none can wrap.
    const std::size_t limit = buffer.size();
    const auto fits = [&](std::size_t offset, std::size_t length) {
      return offset <= limit && length <= limit - offset;
    };
    if (!fits(view.byteOffset, view.byteLength))
      fail(std::string(what) + ": buffer view " + std::to_string(a.bufferView) + " reaches past the end of its buffer");
    const std::size_t needed = a.count == 0 ? 0 : (a.count - 1) * stride + element;
    if (a.count != 0 && (a.count - 1) > (std::numeric_limits<std::size_t>::max() - element) / stride)
      fail(std::string(what) + ": accessor count " + std::to_string(a.count) + " is too large");
    if (a.byteOffset > view.byteLength || needed > view.byteLength - a.byteOffset)
      fail(std::string(what) + ": accessor of " + std::to_string(a.count) +
           " elements does not fit in its buffer view");
    return {buffer.data() + view.byteOffset + a.byteOffset, stride};
  }

  std::vector<std::uint32_t> sparse_indices(const tinygltf::Accessor& a, const char* what) const {
    tinygltf::Accessor list;
    list.bufferView = a.sparse.indices.bufferView;
    list.byteOffset = static_cast<std::size_t>(a.sparse.indices.byteOffset);
    list.componentType = a.sparse.indices.componentType;
    list.count = static_cast<std::size_t>(std::max(a.sparse.count, 0));
    list.type = TINYGLTF_TYPE_SCALAR;
    const Span span = elements(list, 1, what);
    std::vector<std::uint32_t> out(list.count);
    for (std::size_t i = 0; i < list.count; ++i) {
      out[i] = integer(span.data + i * span.stride, list.componentType, what);
      if (out[i] >= a.count) fail(std::string(what) + ": sparse index " + std::to_string(out[i]) + " is out of range");
    }
    return out;
  }

  std::uint32_t integer(const unsigned char* p, int type, const char* what) const {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
      default: fail(std::string(what) + ": index component type " + std::to_string(type) + " is not unsigned");
    }
  }

  template <class T>
  static T load(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);  // glTF is little-endian, as is every machine facet targets
    return v;
  }

  static float component(const unsigned char* element, int type, int c, bool normalized) {
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(element + 4 * c);
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const float v = static_cast<std::int8_t>(element[c]);
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? element[c] / 255.0f : element[c];
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const float v = load<std::int16_t>(element + 2 * c);
        return normalized ? std::max(v / 32767.0f, -1.0f) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const float v = load<std::uint16_t>(element + 2 * c);
        return normalized ? v / 65535.0f : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return static_cast<float>(load<std::uint32_t>(element + 4 * c));
      default: return 0.0f;
    }
  }
};

}  // namespace facet
