// splats.cpp - render_splats(): Gaussians projected to 2D, listed per 16x16 tile by depth, blended front to back.
#include "facet/splats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat2x2.hpp>
#include <glm/mat3x3.hpp>

#include "facet/camera.hpp"
#include "facet/detail/bits.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "facet/renderer.hpp"
#include "facet/simd.hpp"
#include "facet/simd_vectors.hpp"

namespace facet {
namespace {

// The paper's rasterizer constants.
constexpr int kTile = 16;                     // pixels a side of a tile
constexpr float kLowPass = 0.3f;              // pixel^2 added to each 2D covariance's diagonal
constexpr float kMaxAlpha = 0.99f;            // no Gaussian is fully opaque
constexpr float kMinAlpha = 1.0f / 255.0f;    // contributions below are skipped
constexpr float kMinTransmittance = 1e-4f;    // a pixel stops before its transmittance falls below
constexpr float kFrustumLimit = 1.3f;         // the Jacobian is taken at most 1.3 times the view's half-extent out
constexpr std::size_t kFootprintsAhead = 8;   // footprints a tile prefetches ahead of the one it blends
// The most (tile, Gaussian) pairs a frame lists: 1 GiB of indices.
constexpr std::size_t kMaxTileEntries = std::size_t{1} << 28;

// The real spherical harmonics' constants of degrees 1 to 3 (degree 0's is kShDegree0), in the paper's order.
constexpr float kSh1 = 0.4886025119029199f;
constexpr float kSh2[] = {1.0925484305920792f, -1.0925484305920792f, 0.31539156525252005f, -1.0925484305920792f,
                          0.5462742152960396f};
constexpr float kSh3[] = {-0.5900435899266435f, 2.890611442640554f, -0.4570457994644658f, 0.3731763325901154f,
                          -0.4570457994644658f, 1.445305721320277f, -0.5900435899266435f};

// One Gaussian as the tiles see it.
struct Footprint {
  float x = 0.0f, y = 0.0f;                  // centre, in screen pixels (facet's: pixel i's centre is i + 0.5)
  float conic_a = 0.0f, conic_b = 0.0f, conic_c = 0.0f;  // the inverse of the 2D covariance [[a, b], [b, c]]
  float opacity = 0.0f;
  float least_power = 0.0f;  // ln(1 / (255 opacity)): below it, alpha is under 1/255
  glm::vec3 color{0.0f};
  float window_z = 0.0f;                     // 0..1, against the target's depth
  float view_depth = 0.0f;                   // the centre's distance along the view axis
  int first_row = 0, last_row = -1;  // the rows whose alpha can reach 1/255, a pixel of margin added
};

// Which tiles a Gaussian reaches, inclusive; none when x1 < x0 (culled).
struct TileRect {
  std::uint16_t x0 = 1, y0 = 1, x1 = 0, y1 = 0;
  bool empty() const { return x1 < x0; }
};

// A projected Gaussian: its footprint, its tiles and its view depth (the sort key).
struct Projected {
  Footprint footprint;
  TileRect tiles;
  float depth = 0.0f;
};

// d(screen)/d(view-space point) at `q`, the projection's Jacobian (2x3, glm's column-major: J[column][row]).
glm::mat3x2 screen_jacobian(const glm::mat4& clip_from_view, glm::vec3 q, int width, int height) {
  const glm::vec4 clip = clip_from_view * glm::vec4(q, 1.0f);
  const float w2 = clip.w * clip.w;
  glm::mat3x2 j;
  for (int c = 0; c < 3; ++c) {
    const glm::vec4 column = clip_from_view[c];
    j[c][0] = 0.5f * static_cast<float>(width) * (column.x * clip.w - clip.x * column.w) / w2;
    j[c][1] = -0.5f * static_cast<float>(height) * (column.y * clip.w - clip.y * column.w) / w2;
  }
  return j;
}

// The view-space point at q's depth whose normalised x and y are q's clamped to +-kFrustumLimit, as the paper clamps
// before taking the Jacobian (so that Gaussians far off screen get no huge footprint). For the projections whose x
// and y rows do not mix x and y and whose w depends on depth alone (perspective, off-centre or not, and
// orthographic); q itself for any other.
glm::vec3 clamp_to_frustum(const glm::mat4& p, glm::vec3 q) {
  if (p[1][0] != 0.0f || p[0][1] != 0.0f || p[0][3] != 0.0f || p[1][3] != 0.0f || p[0][0] == 0.0f ||
      p[1][1] == 0.0f)
    return q;
  const float w = p[2][3] * q.z + p[3][3];
  const float ndc_x = (p[0][0] * q.x + p[2][0] * q.z + p[3][0]) / w;
  const float ndc_y = (p[1][1] * q.y + p[2][1] * q.z + p[3][1]) / w;
  const float x = std::clamp(ndc_x, -kFrustumLimit, kFrustumLimit), y = std::clamp(ndc_y, -kFrustumLimit, kFrustumLimit);
  if (x != ndc_x) q.x = (x * w - p[2][0] * q.z - p[3][0]) / p[0][0];
  if (y != ndc_y) q.y = (y * w - p[2][1] * q.z - p[3][1]) / p[1][1];
  return q;
}

// Projects Gaussian i; a culled one reaches no tile.
Projected project(const GaussianSplats& splats, std::size_t i, const glm::mat4& view_from_object,
                  const glm::mat4& world_from_object, const glm::mat4& clip_from_view, glm::vec3 eye, int width,
                  int height, int tiles_x, int tiles_y) {
  Projected projected;
  Footprint& g = projected.footprint;
  const glm::vec3 q = glm::vec3(view_from_object * glm::vec4(splats.positions[i], 1.0f));
  const glm::vec4 clip = clip_from_view * glm::vec4(q, 1.0f);
  if (!(clip.w > 0.0f)) return projected;
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  if (!(ndc.z >= -1.0f && ndc.z <= 1.0f)) return projected;  // before the near plane or past the far one
  g.x = (1.0f + ndc.x) * 0.5f * static_cast<float>(width);
  g.y = (1.0f - ndc.y) * 0.5f * static_cast<float>(height);
  g.window_z = ndc.z * 0.5f + 0.5f;
  projected.depth = -q.z;
  g.view_depth = -q.z;

  // Covariance: 3D in object space, R S S^T R^T, carried to view space and through the projection's Jacobian.
  const glm::mat3 rotation = glm::mat3_cast(splats.rotations[i]);
  const glm::vec3 s = splats.scales[i];
  const glm::mat3 m = rotation * glm::mat3(s.x, 0.0f, 0.0f, 0.0f, s.y, 0.0f, 0.0f, 0.0f, s.z);
  const glm::mat3 t3 = glm::mat3(view_from_object) * m;  // view-space axes of the Gaussian, scaled
  const glm::mat3x2 j = screen_jacobian(clip_from_view, clamp_to_frustum(clip_from_view, q), width, height);
  const glm::mat3x2 t = j * t3;  // 2x3: the Gaussian's axes on screen
  const float a = glm::dot(glm::vec3(t[0][0], t[1][0], t[2][0]), glm::vec3(t[0][0], t[1][0], t[2][0])) + kLowPass;
  const float b = glm::dot(glm::vec3(t[0][0], t[1][0], t[2][0]), glm::vec3(t[0][1], t[1][1], t[2][1]));
  const float c = glm::dot(glm::vec3(t[0][1], t[1][1], t[2][1]), glm::vec3(t[0][1], t[1][1], t[2][1])) + kLowPass;
  const float det = a * c - b * b;
  if (!(det > 0.0f) || !std::isfinite(det)) return projected;
  g.conic_a = c / det;
  g.conic_b = -b / det;
  g.conic_c = a / det;
  // Three standard deviations along the larger axis.
  const float mid = 0.5f * (a + c);
  const float largest = mid + std::sqrt(std::max(0.1f, mid * mid - det));
  const float radius = std::ceil(3.0f * std::sqrt(largest));
  // A pixel takes the Gaussian where opacity * exp(-q / 2) >= 1/255, q = d^T cov^-1 d: inside the ellipse q = k2,
  // k2 = 2 ln(255 opacity), which reaches sqrt(k2 a) across and sqrt(k2 c) up and down. The tiles the paper lists
  // (three standard deviations of the larger axis) that lie wholly outside it would add nothing, and neither would
  // the rows of a listed tile outside it: they are not visited.
  g.opacity = splats.opacities[i];
  if (!(g.opacity * 255.0f >= 1.0f)) return Projected{};
  g.least_power = -std::log(255.0f * g.opacity);
  const float k2 = -2.0f * g.least_power;
  const float reach_x = std::sqrt(k2 * a) + 1.0f, reach_y = std::sqrt(k2 * c) + 1.0f;
  const float span_x = std::min(radius, reach_x), span_y = std::min(radius, reach_y);
  // In the paper's pixel coordinates (facet's minus 0.5), as its rasterizer bounds them.
  const float px = g.x - 0.5f, py = g.y - 0.5f;
  if (!(px + span_x >= 0.0f && py + span_y >= 0.0f && px - span_x < static_cast<float>(width) &&
        py - span_y < static_cast<float>(height)))
    return Projected{};
  // Bounds clamped as floats before they become integers (a footprint may be far larger than the target).
  const auto clamped = [](float v, int last) { return static_cast<int>(std::clamp(v, 0.0f, static_cast<float>(last))); };
  TileRect& rect = projected.tiles;
  rect.x0 = static_cast<std::uint16_t>(clamped(std::floor((px - span_x) / kTile), tiles_x - 1));
  rect.y0 = static_cast<std::uint16_t>(clamped(std::floor((py - span_y) / kTile), tiles_y - 1));
  rect.x1 = static_cast<std::uint16_t>(clamped(std::floor((px + span_x) / kTile), tiles_x - 1));
  rect.y1 = static_cast<std::uint16_t>(clamped(std::floor((py + span_y) / kTile), tiles_y - 1));
  g.first_row = clamped(std::floor(py - reach_y), height - 1);
  g.last_row = clamped(std::ceil(py + reach_y), height - 1);
  const glm::vec3 centre = glm::vec3(world_from_object * glm::vec4(splats.positions[i], 1.0f));
  const glm::vec3 to_centre = centre - eye;
  const float length = glm::length(to_centre);
  g.color = splat_color(splats, i, length > 0.0f ? to_centre / length : glm::vec3(0.0f, 0.0f, -1.0f));
  return projected;
}

// exp(x) for x <= 0 in lanes, from exact operations (so every CPU level rounds alike): 2^(x log2 e) as a power of
// two times a degree-6 polynomial of the fraction (relative error under 1e-5, far below an 8-bit step). Below -30
// it is exp(-30), which any opacity makes an alpha under 1/255.
template <class L>
FACET_LANES_INLINE simd::FloatT<L> exp_nonpositive(simd::FloatT<L> x) {
  using namespace simd;
  x = select(x > -30.0f, x, splat<L>(-30.0f));
  const FloatT<L> t = x * 1.44269504f, whole = simd::floor(t), f = t - whole;
  const FloatT<L> p =
      1.0f + f * (0.693147181f + f * (0.240226507f + f * (0.0555041087f + f * (0.00961812911f +
                                                                                f * (0.00133335581f + f * 0.000154035304f)))));
  return p * bit_cast<FloatT<L>>((truncate(whole) + 127) << 23);
}

// Blends the tile's Gaussians (front to back) into its pixels of `color`. Each row of 16 pixels is one lane value
// per quantity, and each Gaussian visits only the rows it reaches; a row whose pixels are all done is skipped, and
// the tile stops when every row is. Each pixel sees the same operations in the same order as one looping over its
// own list.
// Where the target keeps depth (`depth` not null), a pixel the Gaussians cover at least half (1 - transmittance >= 0.5)
// takes their blended view depth, sum(alpha T depth) / sum(alpha T), as window depth (`window_of`): the depth and
// mask outputs then show the splats as they show surfaces.
template <class L, class WindowOf>
FACET_LANES_INLINE void blend_tile(const Footprint* footprints, const std::uint32_t* list, std::size_t count, int x0,
                                   int y0, int width, int height, std::uint32_t* color, float* depth,
                                   const WindowOf& window_of) {
  using namespace simd;
  FACET_LANE_TYPES(L);
  static_assert(kTile == kLanes);
  const int x1 = std::min(width, x0 + kTile), y1 = std::min(height, y0 + kTile);
  const int n = x1 - x0, rows = y1 - y0;
  const Float px = to_float(kLaneIndexT<L> + x0) + 0.5f;
  Float transmittance[kTile], red[kTile], green[kTile], blue[kTile], surface[kTile], distance[kTile];
  Mask active[kTile];
  std::uint32_t alive = 0;  // a bit per row with a pixel still taking Gaussians
  for (int r = 0; r < rows; ++r) {
    alignas(64) float surface_row[kLanes];
    for (int k = 0; k < kLanes; ++k)
      surface_row[k] = depth && k < n ? depth[static_cast<std::size_t>(y0 + r) * width + x0 + k] : 2.0f;
    surface[r] = load<Float>(surface_row);
    transmittance[r] = splat<L>(1.0f), red[r] = green[r] = blue[r] = distance[r] = splat<L>(0.0f);
    active[r] = kLaneIndexT<L> < n;
    alive |= 1u << r;
  }
  for (std::size_t e = 0; e < count && alive; ++e) {
    // Each footprint is read once per tile, from anywhere in the frame's: asked for a few ahead.
    if (e + kFootprintsAhead < count) __builtin_prefetch(footprints + list[e + kFootprintsAhead]);
    const Footprint& g = footprints[list[e]];
    const int first = std::max(g.first_row - y0, 0), last = std::min(g.last_row - y0, rows - 1);
    const Float dx = g.x - px;
    for (int r = first; r <= last; ++r) {
      if (!(alive >> r & 1u)) continue;
      // The paper's operations in its order: d = centre - pixel, power = -(a dx^2 + c dy^2) / 2 - b dx dy.
      const float dy = g.y - (static_cast<float>(y0 + r) + 0.5f);
      const Float power = -0.5f * (g.conic_a * dx * dx + g.conic_c * (dy * dy)) - g.conic_b * dx * dy;
      // Most rows a Gaussian reaches are its rim, where no lane's alpha reaches 1/255 (the margin keeps rounding out
      // of it): the rest of the row's work is skipped there.
      if (lane_bits(power > g.least_power - 1e-3f) == 0) continue;
      const Float raw = g.opacity * exp_nonpositive<L>(power);
      const Float alpha = select(raw < kMaxAlpha, raw, splat<L>(kMaxAlpha));
      const Float next = transmittance[r] * (1.0f - alpha);
      Mask takes = active[r] & ~(power > 0.0f) & ~(alpha < kMinAlpha) & (surface[r] > g.window_z);
      const Mask stops = takes & (next < kMinTransmittance);
      active[r] = active[r] & ~stops;
      takes = takes & ~stops;
      const Float weight = alpha * transmittance[r];
      red[r] = select(takes, red[r] + g.color.r * weight, red[r]);
      green[r] = select(takes, green[r] + g.color.g * weight, green[r]);
      blue[r] = select(takes, blue[r] + g.color.b * weight, blue[r]);
      if (depth) distance[r] = select(takes, distance[r] + g.view_depth * weight, distance[r]);
      transmittance[r] = select(takes, next, transmittance[r]);
      if (lane_bits(active[r]) == 0) alive &= ~(1u << r);
    }
  }
  for (int r = 0; r < rows; ++r) {
    alignas(64) float cr[kLanes], cg[kLanes], cb[kLanes], t[kLanes], d[kLanes];
    store(cr, red[r]), store(cg, green[r]), store(cb, blue[r]), store(t, transmittance[r]), store(d, distance[r]);
    const std::size_t at = static_cast<std::size_t>(y0 + r) * width + x0;
    std::uint32_t* row = color + at;
    for (int k = 0; k < n; ++k) {
      const glm::vec4 under = unpack_rgba8(row[k]);
      row[k] = pack_rgba8(glm::vec4(cr[k] + t[k] * under.r, cg[k] + t[k] * under.g, cb[k] + t[k] * under.b,
                                    (1.0f - t[k]) + t[k] * under.a));
      if (depth && t[k] <= 0.5f) depth[at + k] = std::min(depth[at + k], window_of(d[k] / (1.0f - t[k])));
    }
  }
}

// Gaussian indices ordered by view depth, nearest first, equal depths in index order: a stable radix sort on the
// depths' bits, made monotonic (negative depths, behind an orthographic camera's eye, first). Culled ones are left
// out.
std::vector<std::uint32_t> depth_order(const std::vector<float>& depths, const std::vector<TileRect>& rects) {
  std::vector<std::uint64_t> keys, spare;
  keys.reserve(depths.size());
  for (std::size_t i = 0; i < depths.size(); ++i) {
    if (rects[i].empty()) continue;
    std::uint32_t bits = detail::bit_cast<std::uint32_t>(depths[i]);
    bits = bits >> 31 ? ~bits : bits | 0x80000000u;
    keys.push_back(std::uint64_t{bits} << 32 | i);
  }
  spare.resize(keys.size());
  for (int shift = 32; shift < 64; shift += 16) {
    std::vector<std::size_t> start(65537, 0);
    for (const std::uint64_t k : keys) ++start[((k >> shift) & 0xffffu) + 1];
    for (std::size_t d = 0; d < 65536; ++d) start[d + 1] += start[d];
    for (const std::uint64_t k : keys) spare[start[(k >> shift) & 0xffffu]++] = k;
    keys.swap(spare);
  }
  std::vector<std::uint32_t> order(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = static_cast<std::uint32_t>(keys[i]);
  return order;
}

// check_splats' checks of the arrays, not of their values.
void check_splat_arrays(const GaussianSplats& splats, const std::string& source) {
  const std::size_t n = splats.size();
  if (n > kMaxSplats)
    throw InputError(source, std::to_string(n) + " Gaussians: more than the " + std::to_string(kMaxSplats) +
                                 " a scene may hold");
  if (splats.sh_degree < 0 || splats.sh_degree > 3)
    throw InputError(source, "spherical-harmonics degree " + std::to_string(splats.sh_degree) + ": must be 0..3");
  if (splats.scales.size() != n || splats.rotations.size() != n || splats.opacities.size() != n ||
      splats.sh.size() != n * splats.coefficients())
    throw InputError(source, "the Gaussians' arrays disagree in size with their " + std::to_string(n) + " centres");
}

}  // namespace

void check_splats(const GaussianSplats& splats, const std::string& source) {
  check_splat_arrays(splats, source);
  const std::size_t n = splats.size();
  const auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (std::size_t i = 0; i < n; ++i) {
    const auto which = [&] { return "Gaussian " + std::to_string(i); };
    const glm::quat r = splats.rotations[i];
    if (!finite(splats.positions[i])) throw InputError(source, which() + " has a position that is not finite");
    const glm::vec3 s = splats.scales[i];
    if (!finite(s) || s.x < 0.0f || s.y < 0.0f || s.z < 0.0f)
      throw InputError(source, which() + " has a scale that is negative or not finite");
    if (!(splats.opacities[i] >= 0.0f && splats.opacities[i] <= 1.0f))
      throw InputError(source, which() + " has an opacity outside 0..1");
    const float norm = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
    if (!(std::abs(norm - 1.0f) < 1e-3f)) throw InputError(source, which() + " has a rotation that is not a unit quaternion");
  }
  for (const glm::vec3& c : splats.sh)
    if (!finite(c)) throw InputError(source, "a spherical-harmonics coefficient is not finite");
}

glm::vec3 splat_color(const GaussianSplats& splats, std::size_t index, glm::vec3 d) {
  const glm::vec3* sh = splats.sh.data() + index * splats.coefficients();
  glm::vec3 result = kShDegree0 * sh[0];
  if (splats.sh_degree > 0) {
    const float x = d.x, y = d.y, z = d.z;
    result = result - kSh1 * y * sh[1] + kSh1 * z * sh[2] - kSh1 * x * sh[3];
    if (splats.sh_degree > 1) {
      const float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
      result = result + kSh2[0] * xy * sh[4] + kSh2[1] * yz * sh[5] + kSh2[2] * (2.0f * zz - xx - yy) * sh[6] +
               kSh2[3] * xz * sh[7] + kSh2[4] * (xx - yy) * sh[8];
      if (splats.sh_degree > 2)
        result = result + kSh3[0] * y * (3.0f * xx - yy) * sh[9] + kSh3[1] * xy * z * sh[10] +
                 kSh3[2] * y * (4.0f * zz - xx - yy) * sh[11] + kSh3[3] * z * (2.0f * zz - 3.0f * xx - 3.0f * yy) * sh[12] +
                 kSh3[4] * x * (4.0f * zz - xx - yy) * sh[13] + kSh3[5] * z * (xx - yy) * sh[14] +
                 kSh3[6] * x * (xx - 3.0f * yy) * sh[15];
    }
  }
  return glm::max(result + 0.5f, glm::vec3(0.0f));
}

void render_splats(Renderer& renderer, Framebuffer& target, const View& view, const GaussianSplats& splats,
                   const glm::mat4& world_from_object) {
  check_splat_arrays(splats, "splats");
  const int width = target.width(), height = target.height();
  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  const glm::mat4 view_from_object = view.view_from_world * world_from_object;
  const glm::vec3 eye = glm::vec3(glm::inverse(view.view_from_world)[3]);

  // Projection, a chunk of Gaussians per task, into three arrays: what the tiles blend, the tiles each reaches
  // and the depth each is sorted by.
  const std::size_t n = splats.size();
  std::vector<Footprint> footprints(n);
  std::vector<TileRect> rects(n);
  std::vector<float> depths(n);
  constexpr std::size_t kChunk = 4096;
  renderer.parallel_for((n + kChunk - 1) / kChunk, [&](std::size_t chunk) {
    for (std::size_t i = chunk * kChunk; i < std::min(n, (chunk + 1) * kChunk); ++i) {
      const Projected p = project(splats, i, view_from_object, world_from_object, view.clip_from_view, eye, width,
                                  height, tiles_x, tiles_y);
      footprints[i] = p.footprint, rects[i] = p.tiles, depths[i] = p.depth;
    }
  });

  // Each tile's list, front to back: the Gaussians binned in depth order, in kBinParts consecutive parts of that
  // order on the threads. Each part counts its entries per tile, the counts give every part its place in every
  // tile's list (a part's entries after those of the parts before it), and each part writes its own.
  const std::vector<std::uint32_t> order = depth_order(depths, rects);
  const std::size_t tiles = static_cast<std::size_t>(tiles_x) * tiles_y;
  constexpr std::size_t kBinParts = 16;
  const std::size_t part_size = (order.size() + kBinParts - 1) / kBinParts;
  const auto for_each_tile_of = [&](std::size_t part, auto&& visit) {
    const std::size_t end = std::min(order.size(), (part + 1) * part_size);
    for (std::size_t k = part * part_size; k < end; ++k) {
      const TileRect& r = rects[order[k]];
      for (int ty = r.y0; ty <= r.y1; ++ty)
        for (int tx = r.x0; tx <= r.x1; ++tx) visit(static_cast<std::size_t>(ty) * tiles_x + tx, order[k]);
    }
  };
  std::vector<std::size_t> cursor(kBinParts * tiles, 0);  // part p's place in tile t's list: cursor[p * tiles + t]
  renderer.parallel_for(kBinParts, [&](std::size_t part) {
    for_each_tile_of(part, [&](std::size_t tile, std::uint32_t) { ++cursor[part * tiles + tile]; });
  });
  std::vector<std::size_t> first(tiles + 1, 0);
  for (std::size_t t = 0; t < tiles; ++t) {
    std::size_t at = first[t];
    for (std::size_t part = 0; part < kBinParts; ++part) {
      std::size_t& place = cursor[part * tiles + t];
      const std::size_t count = place;
      place = at;
      at += count;
    }
    first[t + 1] = at;
  }
  if (first[tiles] > kMaxTileEntries)
    throw std::invalid_argument("splats: the Gaussians reach " + std::to_string(first[tiles]) +
                                " tiles in all, more than the " + std::to_string(kMaxTileEntries) +
                                " a frame may list");
  std::vector<std::uint32_t> entries(first[tiles]);
  renderer.parallel_for(kBinParts, [&](std::size_t part) {
    for_each_tile_of(part, [&](std::size_t tile, std::uint32_t i) { entries[cursor[part * tiles + tile]++] = i; });
  });

  std::uint32_t* color = target.mutable_color().data();
  float* depth = target.keeps_depth() ? target.mutable_depth().data() : nullptr;
  // A view depth's window depth on the view axis (x and y of the projections facet makes do not move it).
  const glm::mat4& p = view.clip_from_view;
  const auto window_of = [&p](float distance) {
    const float z = -distance, w = p[2][3] * z + p[3][3];
    return std::clamp((p[2][2] * z + p[3][2]) / w * 0.5f + 0.5f, 0.0f, 1.0f);
  };
  renderer.parallel_for(tiles, [&](std::size_t tile) {
    if (first[tile] == first[tile + 1]) return;
    const int tx = static_cast<int>(tile % static_cast<std::size_t>(tiles_x));
    const int ty = static_cast<int>(tile / static_cast<std::size_t>(tiles_x));
    detail::at_cpu_level([&]<class L>(L) __attribute__((always_inline)) {
      blend_tile<L>(footprints.data(), entries.data() + first[tile], first[tile + 1] - first[tile], tx * kTile,
                    ty * kTile, width, height, color, depth, window_of);
    });
  });
}

}  // namespace facet
