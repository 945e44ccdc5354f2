// test_simd.cpp - the lane maths with a uniform (glm::vec3) operand gives, lane for lane, what glm gives per pixel.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <glm/glm.hpp>

#include "facet/simd.hpp"

namespace facet::simd_tests {
namespace {

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// The bits of a number (so -0 and +0 differ); every NaN as one value, since which NaN an invalid operation returns
// may differ between the compiler's constant folding and the CPU.
std::uint32_t bits(float v) { return std::isnan(v) ? 0x7fc00000u : std::bit_cast<std::uint32_t>(v); }

// Lane values that exercise the sign of zero, NaN, infinities and ordinary numbers.
simd::Vec3 awkward_lanes() {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float values[simd::kLanes] = {0.0f, -0.0f, 1.5f, -2.25f, nan,   inf,  -inf, 1e-30f,
                                      3.0f, -7.0f, 0.1f, 1e30f,  -0.0f, 2.0f, 0.5f, -1e-30f};
  simd::Vec3 v;
  for (int k = 0; k < simd::kLanes; ++k) {
    v.x[k] = values[k];
    v.y[k] = values[(k + 5) % simd::kLanes];
    v.z[k] = values[(k + 11) % simd::kLanes];
  }
  return v;
}

glm::vec3 lane(const simd::Vec3& v, int k) { return {v.x[k], v.y[k], v.z[k]}; }

void expect_same_bits(const glm::vec3& expected, const simd::Vec3& actual, int k) {
  EXPECT_EQ(bits(expected.x), bits(actual.x[k])) << "lane " << k;
  EXPECT_EQ(bits(expected.y), bits(actual.y[k])) << "lane " << k;
  EXPECT_EQ(bits(expected.z), bits(actual.z[k])) << "lane " << k;
}

TEST(SimdUniformOperands, DifferencesMatchGlmBitForBit) {
  const simd::Vec3 v = awkward_lanes();
  for (const glm::vec3 uniform : {glm::vec3(0.0f, -0.0f, 3.0f), glm::vec3(-0.0f, 1.25f, -4.5f)}) {
    const simd::Vec3 from_uniform = uniform - v, to_uniform = v - uniform;
    for (int k = 0; k < simd::kLanes; ++k) {
      expect_same_bits(uniform - lane(v, k), from_uniform, k);
      expect_same_bits(lane(v, k) - uniform, to_uniform, k);
    }
  }
}

TEST(SimdUniformOperands, DotMatchesGlmBitForBit) {
  const simd::Vec3 v = awkward_lanes();
  const glm::vec3 uniform(0.4f, -0.7f, 0.6f);
  const simd::Float d = simd::dot(v, uniform);
  for (int k = 0; k < simd::kLanes; ++k) EXPECT_EQ(bits(glm::dot(lane(v, k), uniform)), bits(d[k])) << "lane " << k;
}

// simd::bit_cast reads a lane type's bits as another's (std::bit_cast per lane); to_int and to_uint convert values.
TEST(SimdConversions, BitCastKeepsBitsAndConversionsKeepValues) {
  const simd::Vec3 v = awkward_lanes();
  const simd::UInt as_bits = simd::bit_cast<simd::UInt>(v.x);
  const simd::Float back = simd::bit_cast<simd::Float>(as_bits);
  for (int k = 0; k < simd::kLanes; ++k) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(v.x[k]), as_bits[k]) << "lane " << k;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(v.x[k]), std::bit_cast<std::uint32_t>(back[k])) << "lane " << k;
  }
  const simd::Int small = simd::kLaneIndex - 8;
  const simd::UInt wrapped = simd::to_uint(small);
  const simd::Int again = simd::to_int(wrapped);
  for (int k = 0; k < simd::kLanes; ++k) {
    EXPECT_EQ(static_cast<std::uint32_t>(k - 8), wrapped[k]) << "lane " << k;
    EXPECT_EQ(k - 8, again[k]) << "lane " << k;
  }
}

// Every layout holds the same 16 lanes in the same bytes, and each operation gives, lane for lane, what the whole
// layout gives: the lane moves (quads, deinterleaving), masks and their bits, conversions and the maths.
template <class L>
void expect_layout_matches_whole() {
  SCOPED_TRACE(L::parts);
  const simd::Vec3 whole = awkward_lanes();
  simd::Vec3T<L> v;
  std::memcpy(v.x.part, whole.x.part, sizeof v.x.part);
  std::memcpy(v.y.part, whole.y.part, sizeof v.y.part);
  std::memcpy(v.z.part, whole.z.part, sizeof v.z.part);
  const auto same = [](const auto& expected, const auto& actual, const char* what) {
    for (int k = 0; k < simd::kLanes; ++k)
      EXPECT_EQ(std::bit_cast<std::uint32_t>(expected[k]), std::bit_cast<std::uint32_t>(actual[k]))
          << what << ", lane " << k;
  };
  same(simd::quad_top_left(whole.x), simd::quad_top_left(v.x), "quad_top_left");
  same(simd::quad_top_right(whole.x), simd::quad_top_right(v.x), "quad_top_right");
  same(simd::quad_bottom_left(whole.x), simd::quad_bottom_left(v.x), "quad_bottom_left");
  const simd::UInt a = simd::bit_cast<simd::UInt>(whole.y), b = simd::bit_cast<simd::UInt>(whole.z);
  const simd::UIntT<L> al = simd::bit_cast<simd::UIntT<L>>(v.y), bl = simd::bit_cast<simd::UIntT<L>>(v.z);
  same(simd::deinterleave<0>(a, b), simd::deinterleave<0>(al, bl), "even lanes");
  same(simd::deinterleave<1>(a, b), simd::deinterleave<1>(al, bl), "odd lanes");
  EXPECT_EQ(simd::lane_bits(whole.x < whole.y), simd::lane_bits(v.x < v.y));
  EXPECT_EQ(simd::lane_bits(whole.x == whole.x), simd::lane_bits(v.x == v.x));  // NaN lanes clear
  same(simd::kLaneIndex, simd::kLaneIndexT<L>, "lane index");
  same(simd::normalize(whole).y, simd::normalize(v).y, "normalize");
  same(simd::dot(whole, glm::vec3(0.4f, -0.7f, 0.6f)), simd::dot(v, glm::vec3(0.4f, -0.7f, 0.6f)), "dot");
  same(simd::floor(whole.z), simd::floor(v.z), "floor");
  same(simd::clamp(whole.x, 0.0f, 1.0f), simd::clamp(v.x, 0.0f, 1.0f), "clamp");
  same(simd::truncate(simd::clamp(whole.y, -1e6f, 1e6f)), simd::truncate(simd::clamp(v.y, -1e6f, 1e6f)), "truncate");
  same(simd::blend(whole.x < whole.z, whole.y, whole.z), simd::blend(v.x < v.z, v.y, v.z), "blend");
  same(simd::pack_rgba8(simd::Color{whole.x, whole.y, whole.z, simd::splat(0.5f)}),
       simd::pack_rgba8(simd::ColorT<L>{v.x, v.y, v.z, simd::splat<L>(0.5f)}), "pack_rgba8");
  const float table[simd::kLanes] = {3, 1, 4, 1, 5, 9, 2, 6, 5, 3, 5, 8, 9, 7, 9, 3};
  same(simd::gather(table, (simd::kLaneIndex * 7) & 15), simd::gather(table, (simd::kLaneIndexT<L> * 7) & 15), "gather");
}

TEST(SimdLayouts, HalvesAndQuartersMatchTheWholeLayout) {
  expect_layout_matches_whole<simd::Halves>();
  expect_layout_matches_whole<simd::Quarters>();
}

// floor is std::floor in every layout, for any bits (the 128-bit layout rounds by conversion on x86-64).
TEST(SimdLayouts, FloorIsStdFloorForAnyBits) {
  std::uint32_t state = 12345u;
  const auto next = [&state] { return state = state * 1664525u + 1013904223u; };
  const auto check = [](const auto& lanes, const float* in) {
    for (int k = 0; k < simd::kLanes; ++k) EXPECT_EQ(bits(std::floor(in[k])), bits(lanes[k])) << in[k];
  };
  for (int round = 0; round < 4096; ++round) {
    alignas(64) float in[simd::kLanes];
    for (int k = 0; k < simd::kLanes; ++k) {
      const std::uint32_t r = next();
      // Half any bit pattern, half values near whole numbers within +-2^24.
      in[k] = k % 2 ? std::bit_cast<float>(r) : static_cast<float>(static_cast<std::int32_t>(r) >> 7) / 64.0f;
    }
    if (round == 0) in[0] = -0.0f, in[1] = 8388608.5f, in[2] = -8388607.5f, in[3] = -1e-45f;
    check(simd::floor(simd::load<simd::Float>(in)), in);
    check(simd::floor(simd::load<simd::FloatT<simd::Halves>>(in)), in);
    check(simd::floor(simd::load<simd::FloatT<simd::Quarters>>(in)), in);
  }
}

// gather_records: lane k of result c is base[offset[k] + c], in every layout, for records of 2 and 4 floats at any
// offsets (unaligned, repeated, overlapping, in any order).
template <int kFloats, class L>
void expect_records_read(const float* base, const std::int32_t* offsets) {
  const std::array<simd::FloatT<L>, kFloats> got =
      simd::gather_records<kFloats>(base, simd::load<simd::IntT<L>>(offsets));
  for (int c = 0; c < kFloats; ++c)
    for (int k = 0; k < simd::kLanes; ++k)
      EXPECT_EQ(bits(base[offsets[k] + c]), bits(got[static_cast<std::size_t>(c)][k]))
          << kFloats << "-float records, " << L::parts << " parts, float " << c << " of lane " << k;
}

TEST(SimdRecords, GatherRecordsReadsEachLanesRecordInEveryLayout) {
  float base[256];
  for (int i = 0; i < 256; ++i) base[i] = static_cast<float>(i) * 0.5f - 17.0f;
  base[9] = -0.0f;
  alignas(64) std::int32_t offsets[simd::kLanes];
  std::uint32_t state = 7u;
  for (int round = 0; round < 64; ++round) {
    for (int k = 0; k < simd::kLanes; ++k) {
      state = state * 1664525u + 1013904223u;
      offsets[k] = round == 0 ? 9 : static_cast<std::int32_t>(state >> 24);  // 0..255, less room for the record
      offsets[k] = offsets[k] > 252 ? 252 : offsets[k];
    }
    expect_records_read<2, simd::Whole>(base, offsets);
    expect_records_read<2, simd::Halves>(base, offsets);
    expect_records_read<2, simd::Quarters>(base, offsets);
    expect_records_read<4, simd::Whole>(base, offsets);
    expect_records_read<4, simd::Halves>(base, offsets);
    expect_records_read<4, simd::Quarters>(base, offsets);
  }
}

#pragma GCC diagnostic pop

}  // namespace
}  // namespace facet::simd_tests
