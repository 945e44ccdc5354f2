// texture_slots.hpp - names for a material's textures, as bits of a set (which of them read the second uv set).
#pragma once

#include <cstdint>

namespace facet::texture_slot {

inline constexpr std::uint32_t base_color = 1u << 0;
inline constexpr std::uint32_t metallic_roughness = 1u << 1;
inline constexpr std::uint32_t occlusion = 1u << 2;
inline constexpr std::uint32_t emissive = 1u << 3;
inline constexpr std::uint32_t normal = 1u << 4;
inline constexpr std::uint32_t specular = 1u << 5;
inline constexpr std::uint32_t specular_color = 1u << 6;
inline constexpr std::uint32_t clearcoat = 1u << 7;
inline constexpr std::uint32_t clearcoat_roughness = 1u << 8;
inline constexpr std::uint32_t clearcoat_normal = 1u << 9;
inline constexpr std::uint32_t sheen_color = 1u << 10;
inline constexpr std::uint32_t sheen_roughness = 1u << 11;
inline constexpr std::uint32_t transmission = 1u << 12;

}  // namespace facet::texture_slot
