// splat_loader.cpp - Gaussian splat scenes: the 3D Gaussian Splatting paper's PLY layout and the .splat format.
#include "job/io/splat_loader.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "facet/detail/bits.hpp"
#include "facet/error.hpp"
#include "facet/splats.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

// Where each value a Gaussian needs sits among the vertex element's properties (-1: absent).
struct Layout {
  int x = -1, y = -1, z = -1, opacity = -1;
  int dc[3] = {-1, -1, -1}, scale[3] = {-1, -1, -1}, rot[4] = {-1, -1, -1, -1};
  std::vector<int> rest;  // f_rest_0.. in order
};

int index_of(const ply::Element& vertex, const std::string& name) {
  for (std::size_t p = 0; p < vertex.properties.size(); ++p)
    if (vertex.properties[p].name == name) return static_cast<int>(p);
  return -1;
}

Layout layout_of(const ply::Element& vertex, const std::string& source) {
  Layout l;
  l.x = index_of(vertex, "x"), l.y = index_of(vertex, "y"), l.z = index_of(vertex, "z");
  l.opacity = index_of(vertex, "opacity");
  for (int c = 0; c < 3; ++c) {
    l.dc[c] = index_of(vertex, "f_dc_" + std::to_string(c));
    l.scale[c] = index_of(vertex, "scale_" + std::to_string(c));
  }
  for (int c = 0; c < 4; ++c) l.rot[c] = index_of(vertex, "rot_" + std::to_string(c));
  for (int k = 0;; ++k) {
    const int at = index_of(vertex, "f_rest_" + std::to_string(k));
    if (at < 0) break;
    l.rest.push_back(at);
  }
  const auto need = [&](int at, const char* name) {
    if (at < 0) throw InputError(source, std::string("Gaussian splat PLY without the '") + name + "' property");
  };
  need(l.x, "x"), need(l.y, "y"), need(l.z, "z"), need(l.opacity, "opacity");
  need(l.dc[1], "f_dc_1"), need(l.dc[2], "f_dc_2"), need(l.scale[0], "scale_0"), need(l.scale[1], "scale_1");
  need(l.scale[2], "scale_2"), need(l.rot[1], "rot_1"), need(l.rot[2], "rot_2"), need(l.rot[3], "rot_3");
  for (const ply::Property& p : vertex.properties)
    if (p.list) throw InputError(source, "Gaussian splat PLY with a list property ('" + p.name + "') in 'vertex'");
  const std::size_t rest = l.rest.size();
  if (rest != 0 && rest != 9 && rest != 24 && rest != 45)
    throw InputError(source, std::to_string(rest) +
                                 " f_rest properties: spherical harmonics of degree 1, 2 or 3 take 9, 24 or 45");
  return l;
}

int degree_of(std::size_t rest) { return rest == 0 ? 0 : rest == 9 ? 1 : rest == 24 ? 2 : 3; }

// One entry's values, by property, from a binary body in the machine's (kSwap false) or the other byte order.
template <bool kSwap>
void read_binary_entry(const char* at, const std::vector<std::size_t>& offsets, const ply::Element& vertex,
                       double* values) {
  for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
    const char* v = at + offsets[p];
    const auto load = [&]<class T>(T) {
      T raw;
      std::memcpy(&raw, v, sizeof raw);
      if constexpr (kSwap && sizeof(T) == 2)
        raw = detail::bit_cast<T>(__builtin_bswap16(detail::bit_cast<std::uint16_t>(raw)));
      else if constexpr (kSwap && sizeof(T) == 4)
        raw = detail::bit_cast<T>(__builtin_bswap32(detail::bit_cast<std::uint32_t>(raw)));
      else if constexpr (kSwap && sizeof(T) == 8)
        raw = detail::bit_cast<T>(__builtin_bswap64(detail::bit_cast<std::uint64_t>(raw)));
      return static_cast<double>(raw);
    };
    switch (vertex.properties[p].type) {
      case ply::Type::kInt8: values[p] = load(std::int8_t{}); break;
      case ply::Type::kUInt8: values[p] = load(std::uint8_t{}); break;
      case ply::Type::kInt16: values[p] = load(std::int16_t{}); break;
      case ply::Type::kUInt16: values[p] = load(std::uint16_t{}); break;
      case ply::Type::kInt32: values[p] = load(std::int32_t{}); break;
      case ply::Type::kUInt32: values[p] = load(std::uint32_t{}); break;
      case ply::Type::kFloat32: values[p] = load(float{}); break;
      case ply::Type::kFloat64: values[p] = load(double{}); break;
    }
  }
}

float sigmoid(double v) { return static_cast<float>(1.0 / (1.0 + std::exp(-v))); }

// The mesh of a reader's Gaussians, after warning of those it skipped.
Mesh splat_mesh(std::shared_ptr<GaussianSplats> splats, std::size_t unplaced, std::size_t unrotated,
                const std::string& source) {
  if (unplaced)
    warn(source, "skipped " + std::to_string(unplaced) + " Gaussians with a value that is not finite or negative");
  if (unrotated) warn(source, "skipped " + std::to_string(unrotated) + " Gaussians with a zero rotation");
  if (splats->size() == 0) throw InputError(source, "nothing to draw (no Gaussian has finite values)");
  check_splats(*splats, source);
  Mesh mesh;
  mesh.positions = splats->positions;
  mesh.splats = std::move(splats);
  return mesh;
}

}  // namespace

bool is_splat_layout(const ply::Element& vertex) {
  return index_of(vertex, "f_dc_0") >= 0 && index_of(vertex, "opacity") >= 0 && index_of(vertex, "scale_0") >= 0 &&
         index_of(vertex, "rot_0") >= 0;
}

Mesh load_splat_ply(std::string_view bytes, const ply::Header& header, const ply::Element& vertex,
                    const std::string& source) {
  const Layout l = layout_of(vertex, source);
  for (const ply::Element& e : header.elements) {
    if (&e == &vertex) break;
    if (e.count > 0) throw InputError(source, "Gaussian splat PLY with element '" + e.name + "' before 'vertex'");
  }
  if (vertex.count == 0) throw InputError(source, "nothing to draw (no Gaussians)");
  if (vertex.count > kMaxSplats)
    throw InputError(source, std::to_string(vertex.count) + " Gaussians: more than the " + std::to_string(kMaxSplats) +
                                 " a scene may hold");
  const std::size_t body_bytes = bytes.size() - header.body_offset;
  ply::check_counts(header, body_bytes, source);

  auto splats = std::make_shared<GaussianSplats>();
  splats->sh_degree = degree_of(l.rest.size());
  const std::size_t n = static_cast<std::size_t>(vertex.count), coefficients = splats->coefficients();
  const std::size_t per_channel = l.rest.size() / 3;
  splats->positions.reserve(n), splats->scales.reserve(n), splats->rotations.reserve(n);
  splats->opacities.reserve(n), splats->sh.reserve(n * coefficients);
  std::size_t unplaced = 0, unrotated = 0, unscaled = 0;
  std::vector<double> values(vertex.properties.size());
  // Adds the entry in `values`, or counts why it is skipped.
  const auto add = [&]() {
    const glm::vec3 position(static_cast<float>(values[l.x]), static_cast<float>(values[l.y]),
                             static_cast<float>(values[l.z]));
    const glm::vec3 scale(std::exp(values[l.scale[0]]), std::exp(values[l.scale[1]]), std::exp(values[l.scale[2]]));
    glm::quat rotation(static_cast<float>(values[l.rot[0]]), static_cast<float>(values[l.rot[1]]),
                       static_cast<float>(values[l.rot[2]]), static_cast<float>(values[l.rot[3]]));
    const float norm = std::sqrt(rotation.w * rotation.w + rotation.x * rotation.x + rotation.y * rotation.y +
                                 rotation.z * rotation.z);
    const auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!finite(position)) return void(++unplaced);
    if (!(norm > 0.0f) || !std::isfinite(norm)) return void(++unrotated);
    if (!finite(scale)) return void(++unscaled);
    glm::vec3 sh[16];
    for (int c = 0; c < 3; ++c) {
      sh[0][c] = static_cast<float>(values[l.dc[c]]);
      for (std::size_t k = 1; k < coefficients; ++k)
        sh[k][c] = static_cast<float>(values[l.rest[static_cast<std::size_t>(c) * per_channel + k - 1]]);
    }
    for (std::size_t k = 0; k < coefficients; ++k)
      if (!finite(sh[k])) return void(++unplaced);
    const float opacity = sigmoid(values[l.opacity]);
    if (!std::isfinite(opacity)) return void(++unplaced);
    splats->positions.push_back(position);
    splats->scales.push_back(scale);
    splats->rotations.push_back(rotation * (1.0f / norm));
    splats->opacities.push_back(opacity);
    splats->sh.insert(splats->sh.end(), sh, sh + coefficients);
  };

  const char* body = bytes.data() + header.body_offset;
  if (header.encoding == ply::Encoding::kAscii) {
    TextCursor text(body, bytes.data() + bytes.size(), header.body_line);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t v = 0; v < values.size(); ++v) {
        const std::string_view token = text.next();
        if (!parse_real(token, values[v]))
          throw InputError(source, "line " + std::to_string(text.line()) + ": property '" +
                                       vertex.properties[v].name + "' of Gaussian " + std::to_string(i) + " is " +
                                       (token.empty() ? "missing" : "not a number"));
      }
      add();
    }
  } else {
    std::vector<std::size_t> offsets(vertex.properties.size());
    std::size_t stride = 0;
    for (std::size_t p = 0; p < offsets.size(); ++p) {
      offsets[p] = stride;
      stride += ply::size_of(vertex.properties[p].type);
    }
    // check_counts has made sure the body holds every entry.
    const bool swap = (header.encoding == ply::Encoding::kBinaryLittleEndian) != detail::kLittleEndian;
    for (std::size_t i = 0; i < n; ++i) {
      const char* at = body + i * stride;
      if (swap) read_binary_entry<true>(at, offsets, vertex, values.data());
      else read_binary_entry<false>(at, offsets, vertex, values.data());
      add();
    }
  }
  if (unscaled) warn(source, "skipped " + std::to_string(unscaled) + " Gaussians with a scale too large for a float");
  return splat_mesh(std::move(splats), unplaced, unrotated, source);
}

Mesh load_splat(std::string_view bytes, const std::string& source) {
  constexpr std::size_t kRecord = 32;
  if (bytes.size() % kRecord != 0)
    throw InputError(source, std::to_string(bytes.size()) + " bytes: not a whole number of 32-byte Gaussians");
  const std::size_t n = bytes.size() / kRecord;
  if (n > kMaxSplats)
    throw InputError(source, std::to_string(n) + " Gaussians: more than the " + std::to_string(kMaxSplats) +
                                 " a scene may hold");
  auto splats = std::make_shared<GaussianSplats>();
  splats->positions.reserve(n), splats->scales.reserve(n), splats->rotations.reserve(n);
  splats->opacities.reserve(n), splats->sh.reserve(n);
  std::size_t unplaced = 0, unrotated = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const char* at = bytes.data() + i * kRecord;
    float f[6];
    for (int k = 0; k < 6; ++k) {
      std::uint32_t bits;
      std::memcpy(&bits, at + 4 * k, sizeof bits);
      if constexpr (!detail::kLittleEndian) bits = __builtin_bswap32(bits);
      f[k] = detail::bit_cast<float>(bits);
    }
    const auto byte = [&](int k) { return static_cast<float>(static_cast<unsigned char>(at[24 + k])); };
    const glm::vec3 position(f[0], f[1], f[2]), scale(f[3], f[4], f[5]);
    glm::quat rotation((byte(4) - 128.0f) / 128.0f, (byte(5) - 128.0f) / 128.0f, (byte(6) - 128.0f) / 128.0f,
                       (byte(7) - 128.0f) / 128.0f);
    const float norm = std::sqrt(rotation.w * rotation.w + rotation.x * rotation.x + rotation.y * rotation.y +
                                 rotation.z * rotation.z);
    const auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!finite(position) || !finite(scale) || scale.x < 0.0f || scale.y < 0.0f || scale.z < 0.0f) {
      ++unplaced;
      continue;
    }
    if (!(norm > 0.0f)) {
      ++unrotated;
      continue;
    }
    splats->positions.push_back(position);
    splats->scales.push_back(scale);
    splats->rotations.push_back(rotation * (1.0f / norm));
    splats->opacities.push_back(byte(3) / 255.0f);
    // The colour as shown is the degree-0 term plus 0.5.
    splats->sh.push_back((glm::vec3(byte(0), byte(1), byte(2)) / 255.0f - 0.5f) / kShDegree0);
  }
  return splat_mesh(std::move(splats), unplaced, unrotated, source);
}

}  // namespace facet
