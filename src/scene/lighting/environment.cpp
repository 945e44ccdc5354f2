// environment.cpp - prefiltering an environment image: irradiance harmonics and GGX-convolved octahedral levels.
#include "facet/environment.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

#include "facet/shaders/brdf.hpp"
#include "core/in_parts.hpp"
#include "scene/lighting/sampling.hpp"

namespace facet {

namespace {

constexpr float kPi = brdf::kPi;

// Halves an equirectangular image (2x2 box) until it is at most max_width wide: prefiltering needs no more detail
// than the octahedral maps hold.
EnvironmentImage shrink(const EnvironmentImage& image, int max_width) {
  EnvironmentImage out = image;
  while (out.width > max_width && out.height >= 2) {
    EnvironmentImage half;
    half.width = out.width / 2;
    half.height = out.height / 2;
    half.texels.resize(static_cast<std::size_t>(half.width) * static_cast<std::size_t>(half.height));
    for (int y = 0; y < half.height; ++y)
      for (int x = 0; x < half.width; ++x) {
        const auto at = [&](int dx, int dy) {
          return out.texels[static_cast<std::size_t>(2 * y + dy) * static_cast<std::size_t>(out.width) +
                            static_cast<std::size_t>(2 * x + dx)];
        };
        half.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(half.width) + static_cast<std::size_t>(x)] =
            (at(0, 0) + at(1, 0) + at(0, 1) + at(1, 1)) * 0.25f;
      }
    out = std::move(half);
  }
  return out;
}

// Bilinear lookup of an equirectangular image along unit direction d (image space): wraps around in azimuth,
// clamps at the poles.
glm::vec3 sample_equirect(const EnvironmentImage& image, glm::vec3 d) {
  const float u = 0.5f + std::atan2(d.z, d.x) / (2.0f * kPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  const float s = u * static_cast<float>(image.width) - 0.5f, t = v * static_cast<float>(image.height) - 0.5f;
  const float fs = std::floor(s), ft = std::floor(t);
  const float a = s - fs, b = t - ft;
  const int i0 = static_cast<int>(fs), j0 = static_cast<int>(ft);
  const auto at = [&](int i, int j) {
    i = ((i % image.width) + image.width) % image.width;
    j = std::clamp(j, 0, image.height - 1);
    return image
        .texels[static_cast<std::size_t>(j) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(i)];
  };
  return glm::mix(glm::mix(at(i0, j0), at(i0 + 1, j0), a), glm::mix(at(i0, j0 + 1), at(i0 + 1, j0 + 1), a), b);
}

// The real spherical harmonics up to degree 2 at a unit direction, without their constants (folded in later).
std::array<float, 9> sh_polynomials(glm::vec3 d) {
  return {1.0f, d.y, d.z, d.x, d.x * d.y, d.y * d.z, 3.0f * d.z * d.z - 1.0f, d.x * d.z, d.x * d.x - d.y * d.y};
}
// Each basis function's constant, and the cosine lobe's factor for its degree (pi, 2 pi / 3, pi / 4).
constexpr std::array<float, 9> kShConstant = {0.282095f, 0.488603f, 0.488603f, 0.488603f, 1.092548f,
                                              1.092548f, 0.315392f, 1.092548f, 0.546274f};
constexpr std::array<float, 9> kCosineLobe = {kPi,        2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f, 2.0f * kPi / 3.0f,
                                              kPi / 4.0f, kPi / 4.0f,        kPi / 4.0f,        kPi / 4.0f,
                                              kPi / 4.0f};

// Projects radiance onto the harmonics (each texel weighted by its solid angle) and convolves with the cosine lobe:
// E(n) = sum_i lobe_i L_i Y_i(n), returned with each term's constant folded in so that E is a plain polynomial.
std::array<glm::vec3, 9> irradiance_harmonics(const EnvironmentImage& image, const glm::mat3& world_from_image) {
  std::array<glm::vec3, 9> l{};
  const float dphi = 2.0f * kPi / static_cast<float>(image.width), dtheta = kPi / static_cast<float>(image.height);
  const ColumnAzimuths phi = column_azimuths(image.width);
  for (int y = 0; y < image.height; ++y) {
    const float theta = (static_cast<float>(y) + 0.5f) * dtheta;
    const float cos_theta = std::cos(theta), sin_theta = std::sin(theta);
    const float weight = sin_theta * dphi * dtheta;
    for (int x = 0; x < image.width; ++x) {
      const std::size_t column = static_cast<std::size_t>(x);
      const glm::vec3 d =
          world_from_image * glm::vec3(phi.cos[column] * sin_theta, cos_theta, phi.sin[column] * sin_theta);
      const glm::vec3 radiance = image.texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                              static_cast<std::size_t>(x)] *
                                 weight;
      const std::array<float, 9> p = sh_polynomials(d);
      for (std::size_t i = 0; i < 9; ++i) l[i] += radiance * (p[i] * kShConstant[i]);
    }
  }
  for (std::size_t i = 0; i < 9; ++i) l[i] *= kCosineLobe[i] * kShConstant[i];
  return l;
}

// One importance sample of the GGX lobe around the normal, in the normal's frame (z along it), with the source
// level it reads: filtered importance sampling (Colbert and Krivanek, GPU Gems 3 ch. 20) takes each sample from
// the level whose texels cover about the sample's solid angle, so few samples give a smooth result.
struct LobeSample {
  glm::vec3 l;   // direction towards the light, n = v = (0, 0, 1)
  float weight;  // NdotL
  float level;
};

std::vector<LobeSample> lobe_samples(float alpha, int count, int source_size, int source_levels) {
  std::vector<LobeSample> samples;
  const float texel_solid_angle = 4.0f * kPi / static_cast<float>(source_size * source_size);
  for (int i = 0; i < count; ++i) {
    const glm::vec2 xi = hammersley(i, count);
    const float phi = 2.0f * kPi * xi.x;
    const float cos_theta = std::sqrt((1.0f - xi.y) / (1.0f + (alpha * alpha - 1.0f) * xi.y));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const glm::vec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
    const glm::vec3 l = 2.0f * h.z * h - glm::vec3(0.0f, 0.0f, 1.0f);
    if (l.z <= 0.0f) continue;
    // pdf of l = D(h) (n.h) / (4 v.h), with v = n: D(h) / 4.
    const float pdf = brdf::distribution_ggx(h.z, alpha) / 4.0f;
    const float sample_solid_angle = 1.0f / (static_cast<float>(count) * pdf);
    const float level = std::clamp(0.5f * std::log2(sample_solid_angle / texel_solid_angle) + 1.0f, 0.0f,
                                   static_cast<float>(source_levels - 1));
    samples.push_back({l, l.z, level});
  }
  return samples;
}

// f over a map's rows in up to 8 parts on threads of their own; a texel's value does not depend on the split.
template <class F>
void fill_in_parallel(OctahedralMap& map, F f) {
  const int rows = map.size();
  const int parts = std::clamp(std::min(static_cast<int>(std::thread::hardware_concurrency()), rows), 1, 8);
  detail::in_parts(parts, [&](int p) {
    map.fill_rows(static_cast<int>(detail::part_begin(static_cast<std::size_t>(rows), p, parts)),
                  static_cast<int>(detail::part_begin(static_cast<std::size_t>(rows), p + 1, parts)), f);
  });
}

// A unit-length frame around n: columns t, b, n.
glm::mat3 frame_around(glm::vec3 n) {
  const glm::vec3 up = std::abs(n.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t = glm::normalize(glm::cross(up, n));
  return glm::mat3(t, glm::cross(n, t), n);
}

}  // namespace

Environment::Environment(const EnvironmentImage& image, float rotation_degrees, float intensity,
                         const glm::mat3& world_from_upright) {
  // The split-sum table (integrated once per process, about a millisecond on one thread) beside the prefiltering,
  // which leaves a core idle in its serial parts. The browser build has no threads.
#if defined(__EMSCRIPTEN__)
  table_ = detail::brdf_table_entries();
#else
  std::future<const glm::vec2*> table = std::async(std::launch::async, detail::brdf_table_entries);
#endif
  if (image.width < 1 || image.height < 1 ||
      image.texels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::invalid_argument("environment: image size and texels do not agree");
  if (!std::isfinite(rotation_degrees)) throw std::invalid_argument("environment rotation: must be finite");
  if (!(intensity >= 0.0f) || !std::isfinite(intensity))
    throw std::invalid_argument("environment intensity: must be finite and not negative");
  const float angle = glm::radians(rotation_degrees);
  // Turning the environment by +angle about +Y (counter-clockwise seen from above) maps image direction d to
  // world direction R d; lookups go the other way.
  const float c = std::cos(angle), s = std::sin(angle);
  const glm::mat3 world_from_image =
      world_from_upright * glm::mat3(glm::vec3(c, 0.0f, -s), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(s, 0.0f, c));
  const glm::mat3 image_from_world = glm::transpose(world_from_image);

  EnvironmentImage small = shrink(image, 512);
  for (glm::vec3& t : small.texels) t *= intensity;
  irradiance_sh_ = irradiance_harmonics(shrink(small, 128), world_from_image);

  // The source: the image resampled into an octahedral map in world space, and its box-filtered chain.
  const int source_size = small.width >= 512 ? 256 : 128;
  std::vector<OctahedralMap> source(1);
  source[0] = OctahedralMap(source_size);
  fill_in_parallel(source[0], [&](glm::vec3 d) { return sample_equirect(small, image_from_world * d); });
  while (source.back().size() > 1) source.push_back(source.back().half());
  const int source_levels = static_cast<int>(source.size());
  const auto source_sample = [&](glm::vec3 d, float level) {
    const int i = static_cast<int>(level);
    const float f = level - static_cast<float>(i);
    const glm::vec3 a = source[static_cast<std::size_t>(i)].sample(d);
    if (f == 0.0f || i + 1 >= source_levels) return a;
    return glm::mix(a, source[static_cast<std::size_t>(i + 1)].sample(d), f);
  };

  levels_[0] = source[0];
  for (int k = 1; k < kRoughnessLevels; ++k) {
    const float roughness = static_cast<float>(k) / static_cast<float>(kRoughnessLevels - 1);
    const std::vector<LobeSample> samples = lobe_samples(roughness * roughness, 32, source_size, source_levels);
    OctahedralMap& level = levels_[static_cast<std::size_t>(k)];
    level = OctahedralMap(std::max(16, source_size >> (k + 1)));
    fill_in_parallel(level, [&](glm::vec3 n) {
      const glm::mat3 frame = frame_around(n);
      glm::vec3 sum(0.0f);
      float weight = 0.0f;
      for (const LobeSample& s : samples) {
        sum += source_sample(frame * s.l, s.level) * s.weight;
        weight += s.weight;
      }
      return weight > 0.0f ? sum / weight : glm::vec3(0.0f);
    });
  }
#if !defined(__EMSCRIPTEN__)
  table_ = table.get();
#endif
}

}  // namespace facet
