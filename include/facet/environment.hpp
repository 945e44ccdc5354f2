// environment.hpp - image-based light: an environment image prefiltered once for diffuse and specular lookups.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "facet/detail/brdf_table.hpp"
#include "facet/detail/octahedral_map.hpp"
#include "facet/simd.hpp"

namespace facet {

// Linear-light radiance over the sphere in an equirectangular image, oriented as three.js maps one: column u (0 at
// the left edge, 1 at the right) looks towards azimuth atan2(z, x) = 2 pi (u - 0.5), so the centre column faces +X
// and the column a quarter to its right +Z; the top row is +Y (up), the bottom row -Y.
struct EnvironmentImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;  // row-major, top row first
};

// Reads a Radiance .hdr (RGBE) or OpenEXR .exr file as linear RGB radiance. Throws InputError(path, problem) for an
// unreadable, malformed or truncated file, one larger than kMaxEnvironmentSize per side, or one with negative,
// NaN or infinite values (named with the texel where they are).
EnvironmentImage read_environment_image(const std::filesystem::path& path);
inline constexpr int kMaxEnvironmentSize = 16384;

// The default light of the physically based look: a neutral photographic studio made by facet (a soft grey dome,
// a darker floor, a large key softbox above and to the front left, a fill to the right and a rim light behind).
EnvironmentImage studio_environment();

// An environment prefiltered for the physically based shaders (built once, then shared by every draw and frame):
// - irradiance: spherical harmonics up to degree 2 of the cosine-weighted irradiance E(n) (Ramamoorthi and
//   Hanrahan, "An Efficient Representation for Irradiance Environment Maps", 2001);
// - radiance: the image convolved with the GGX lobe at kRoughnessLevels roughnesses (0, 0.25, ..., 1), each level
//   an octahedral map, sampled bilinearly and blended between the two nearest roughnesses (Karis, "Real Shading in
//   Unreal Engine 4", 2013: the split sum's first factor, with N = V = R);
// - the split sum's second factor, the table of A and B over NdotV and roughness (brdf_table below).
// `rotation_degrees` turns the image about the up axis (+Y) before use; `world_from_upright` then turns that up
// axis to the world's (a Z-up model's +Z); `intensity` scales its radiance.
class Environment {
 public:
  static constexpr int kRoughnessLevels = 5;

  explicit Environment(const EnvironmentImage& image, float rotation_degrees = 0.0f, float intensity = 1.0f,
                       const glm::mat3& world_from_upright = glm::mat3(1.0f));

  // E(n) for a unit normal n (world space): the light a diffuse surface facing n receives; a Lambertian surface
  // of colour c reflects c E / pi.
  glm::vec3 irradiance(glm::vec3 n) const {
    const std::array<float, 3> e = irradiance(n.x, n.y, n.z);
    return {e[0], e[1], e[2]};
  }
  // The same for F = float or simd::FloatT (16 normals at once), with the same operations in the same order.
  template <class F>
  std::array<F, 3> irradiance(const F& x, const F& y, const F& z) const {
    const auto& c = irradiance_sh_;
    std::array<F, 3> e;
    for (int k = 0; k < 3; ++k)
      e[static_cast<std::size_t>(k)] = c[0][k] + c[1][k] * y + c[2][k] * z + c[3][k] * x + c[4][k] * (x * y) +
                                       c[5][k] * (y * z) + c[6][k] * (3.0f * z * z - 1.0f) + c[7][k] * (x * z) +
                                       c[8][k] * (x * x - y * y);
    return e;
  }

  // The prefiltered radiance arriving along unit direction d for a surface of the given roughness in [0, 1]: the
  // two levels nearest the roughness, each sampled bilinearly, blended linearly.
  glm::vec3 radiance(glm::vec3 d, float roughness) const {
    const float x =
        (roughness > 0.0f ? (roughness < 1.0f ? roughness : 1.0f) : 0.0f) * static_cast<float>(kRoughnessLevels - 1);
    int i = static_cast<int>(x);
    i = i < kRoughnessLevels - 1 ? i : kRoughnessLevels - 1;  // roughness 1 reads the roughest level alone
    const float f = x - static_cast<float>(i);
    const glm::vec2 uv = detail::octahedral_from_direction(d);
    const glm::vec3 a = levels_[static_cast<std::size_t>(i)].sample(uv);
    if (f == 0.0f) return a;  // at a level's own roughness (as the lanes take it: a + (b - a) 0 is a)
    const glm::vec3 b = levels_[static_cast<std::size_t>(i + 1)].sample(uv);
    return a + (b - a) * f;
  }

  // radiance() for 16 directions and roughnesses: the same operations lane for lane, the texels gathered per lane.
  template <class L>
  FACET_LANES_INLINE simd::Vec3T<L> radiance(const simd::Vec3T<L>& d, const simd::FloatT<L>& roughness) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Float x = select(roughness > 0.0f, select(roughness < 1.0f, roughness, splat<L>(1.0f)), splat<L>(0.0f)) *
                    static_cast<float>(kRoughnessLevels - 1);
    Int i = truncate(x);
    i = blend(i < kRoughnessLevels - 1, i, splat<L>(kRoughnessLevels - 1));
    const Float f = x - to_float(i);
    const Vec2 uv = octahedral_lanes(d);
    const auto blend_levels = [&f](const Vec3& a, const Vec3& b) -> Vec3 {
      return {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, a.z + (b.z - a.z) * f};
    };
    // Most materials' roughness is one factor, so every lane reads the same two levels; at a level's own roughness
    // (f = 0, roughness 1 among them) the second adds nothing (a + (b - a) 0 is a, bit for bit).
    const int first = i[0];
    if (lane_bits(i == first) == (1u << kLanes) - 1u) {
      const detail::OctahedralMap& level = levels_[static_cast<std::size_t>(first)];
      const Vec3 a = sample_lanes(level, uv);
      if (lane_bits(f == 0.0f) == (1u << kLanes) - 1u) return a;
      return blend_levels(a, sample_lanes(levels_[static_cast<std::size_t>(first + 1)], uv));
    }
    const Int next = blend(i < kRoughnessLevels - 1, i + 1, i);  // where f is 0
    return blend_levels(sample_lanes(i, uv), sample_lanes(next, uv));
  }

  // The split sum's second factor at NdotV and roughness (brdf_table), from the table this environment holds.
  // ... and for 16 lanes: the same operations, the four table entries gathered per lane.
  template <class L>
  FACET_LANES_INLINE simd::Vec2T<L> split_sum(const simd::FloatT<L>& n_dot_v, const simd::FloatT<L>& roughness) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    constexpr float n = kBrdfTableSize;
    const auto coordinate = [](const Float& v) {
      const Float c = v * n - 0.5f;
      return select(c > 0.0f, select(c < n - 1.0f, c, splat<L>(n - 1.0f)), splat<L>(0.0f));
    };
    const Float s = coordinate(n_dot_v), r = coordinate(roughness);
    const Int i = truncate(s), j = truncate(r);
    const Float a = s - to_float(i), b = r - to_float(j);
    const Int i1 = blend(i + 1 < kBrdfTableSize, i + 1, i), j1 = blend(j + 1 < kBrdfTableSize, j + 1, j);
    // Each entry is two floats (A, B): one record per lane and corner.
    const float* table = &table_[0].x;
    const auto corner = [&](const Int& column, const Int& row) {
      return gather_records<2>(table, (row * kBrdfTableSize + column) * 2);
    };
    const auto t00 = corner(i, j), t10 = corner(i1, j), t01 = corner(i, j1), t11 = corner(i1, j1);
    const auto lerp = [](const Float& p, const Float& q, const Float& w) { return p + (q - p) * w; };
    const Float bottom_x = lerp(t00[0], t10[0], a), bottom_y = lerp(t00[1], t10[1], a);
    const Float top_x = lerp(t01[0], t11[0], a), top_y = lerp(t01[1], t11[1], a);
    return {lerp(bottom_x, top_x, b), lerp(bottom_y, top_y, b)};
  }
  glm::vec2 split_sum(float n_dot_v, float roughness) const {
    return detail::brdf_table_lookup(table_, n_dot_v, roughness);
  }

 private:
  // detail::octahedral_from_direction for 16 directions (the absolute value as std::abs takes it: the sign bit
  // cleared).
  template <class L>
  FACET_LANES_INLINE static simd::Vec2T<L> octahedral_lanes(const simd::Vec3T<L>& d) {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const auto abs = [](const Float& v) { return bit_cast<Float>(bit_cast<Int>(v) & 0x7fffffff); };
    const Float s = abs(d.x) + abs(d.y) + abs(d.z);
    const Float px = d.x / s, pz = d.z / s;
    const Float fx = (1.0f - abs(pz)) * select(px < 0.0f, splat<L>(-1.0f), splat<L>(1.0f));
    const Float fz = (1.0f - abs(px)) * select(pz < 0.0f, splat<L>(-1.0f), splat<L>(1.0f));
    const Mask lower = d.y < 0.0f;
    return {select(lower, fx, px) * 0.5f + 0.5f, select(lower, fz, pz) * 0.5f + 0.5f};
  }
  // detail::OctahedralMap::sample for 16 lanes from one level.
  template <class L>
  FACET_LANES_INLINE static simd::Vec3T<L> sample_lanes(const detail::OctahedralMap& map, const simd::Vec2T<L>& uv) {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const int size = map.size();
    const float n = static_cast<float>(size), hi = n - 1.0f;
    const auto coordinate = [&](const Float& v) {
      const Float c = v * n - 0.5f;
      return select(c > 0.0f, select(c < hi, c, splat<L>(hi)), splat<L>(0.0f));  // as OctahedralMap::sample clamps
    };
    const Float s = coordinate(uv.x), t = coordinate(uv.y);
    const Int i = truncate(s), j = truncate(t);
    const Float a = s - to_float(i), b = t - to_float(j);
    const Int i1 = blend(i + 1 < size, i + 1, splat<L>(size - 1)), j1 = blend(j + 1 < size, j + 1, splat<L>(size - 1));
    const Int row0 = j * size, row1 = j1 * size;
    // Each texel is four floats: one record per lane and corner.
    const float* texels = &map.texels()->x;
    const auto corner = [&](const Int& column, const Int& row) {
      const std::array<Float, 4> t = gather_records<4>(texels, (row + column) * 4);
      return Vec3{t[0], t[1], t[2]};
    };
    return bilinear(corner(i, row0), corner(i1, row0), corner(i, row1), corner(i1, row1), a, b);
  }
  // The bilinear blend of four corners' texels at fractions a (along a row) and b (down), as OctahedralMap::sample
  // takes it.
  template <class L>
  FACET_LANES_INLINE static simd::Vec3T<L> bilinear(const simd::Vec3T<L>& t00, const simd::Vec3T<L>& t10,
                                                    const simd::Vec3T<L>& t01, const simd::Vec3T<L>& t11,
                                                    const simd::FloatT<L>& a, const simd::FloatT<L>& b) {
    using Float = simd::FloatT<L>;
    const auto lerp = [](const Float& p, const Float& q, const Float& w) { return p + (q - p) * w; };
    const simd::Vec3T<L> bottom{lerp(t00.x, t10.x, a), lerp(t00.y, t10.y, a), lerp(t00.z, t10.z, a)};
    const simd::Vec3T<L> top{lerp(t01.x, t11.x, a), lerp(t01.y, t11.y, a), lerp(t01.z, t11.z, a)};
    return {lerp(bottom.x, top.x, b), lerp(bottom.y, top.y, b), lerp(bottom.z, top.z, b)};
  }
  // detail::OctahedralMap::sample for 16 lanes, each from its own level.
  template <class L>
  FACET_LANES_INLINE simd::Vec3T<L> sample_lanes(const simd::IntT<L>& level, const simd::Vec2T<L>& uv) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    Float n;
    for (int k = 0; k < kLanes; ++k) n[k] = static_cast<float>(levels_[static_cast<std::size_t>(level[k])].size());
    const Float hi = n - 1.0f;
    const auto coordinate = [&](const Float& v) {
      const Float c = v * n - 0.5f;
      return select(c > 0.0f, select(c < hi, c, hi), splat<L>(0.0f));  // as OctahedralMap::sample clamps
    };
    const Float s = coordinate(uv.x), t = coordinate(uv.y);
    const Int i = truncate(s), j = truncate(t);
    const Float a = s - to_float(i), b = t - to_float(j);
    Vec3 t00, t10, t01, t11;
    for (int k = 0; k < kLanes; ++k) {
      const detail::OctahedralMap& map = levels_[static_cast<std::size_t>(level[k])];
      const int size = map.size();
      const int i1 = i[k] + 1 < size ? i[k] + 1 : size - 1, j1 = j[k] + 1 < size ? j[k] + 1 : size - 1;
      const glm::vec4* texels = map.texels();
      const glm::vec4 c00 = texels[j[k] * size + i[k]], c10 = texels[j[k] * size + i1];
      const glm::vec4 c01 = texels[j1 * size + i[k]], c11 = texels[j1 * size + i1];
      t00.x[k] = c00.x, t00.y[k] = c00.y, t00.z[k] = c00.z;
      t10.x[k] = c10.x, t10.y[k] = c10.y, t10.z[k] = c10.z;
      t01.x[k] = c01.x, t01.y[k] = c01.y, t01.z[k] = c01.z;
      t11.x[k] = c11.x, t11.y[k] = c11.y, t11.z[k] = c11.z;
    }
    return bilinear(t00, t10, t01, t11, a, b);
  }

  std::array<glm::vec3, 9> irradiance_sh_{};  // E's coefficients with the cosine lobe and basis constants folded in
  std::array<detail::OctahedralMap, kRoughnessLevels> levels_;  // world space, roughest last
  const glm::vec2* table_;                                      // brdf_table's entries
};

// studio_environment() prefiltered, once per process (thread-safe): the default light of the physically based look.
std::shared_ptr<const Environment> studio_lighting();

// The split-sum table: for NdotV and roughness in [0, 1], A and B such that the directional albedo of the GGX
// specular BRDF with Smith height-correlated visibility is f0 A + f90 B (Karis 2013), integrated numerically once
// (kBrdfTableSize^2 entries, importance-sampled) and read bilinearly.
glm::vec2 brdf_table(float n_dot_v, float roughness);

}  // namespace facet
