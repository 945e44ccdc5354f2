// setup.cpp - from clip-space primitives to fixed-point edges, interpolation planes and tile bins.
#include "core/setup/setup.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/clip/clip.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/framebuffer.hpp"
#include "core/setup/project.hpp"

namespace facet::detail {
namespace {

// A vertex after the w-divide and the viewport transform, before snapping. b1_w and b2_w are the source
// barycentric weights over w, which stay linear in screen space.
struct ScreenVertex {
  float x, y, z, inv_w, b1_w, b2_w;
};

// The same after snapping: what a set-up triangle is built from.
struct SnappedVertex {
  std::int32_t x, y;
  float z, inv_w, b1_w, b2_w;
};

// What a set-up triangle's planes interpolate, per corner in clockwise order: window z, 1/w, and the source
// barycentric weights 1 and 2 over w.
struct CornerValues {
  float value[4][3];
};

// Division by the sub-pixel scale rounding towards minus infinity: C++20 defines >> on negative values as an
// arithmetic shift, which is exactly that.
std::int64_t floor_div_subpixel(std::int64_t a) { return a >> kSubpixelBits; }

ScreenVertex to_screen(const glm::vec4& clip, const glm::vec3& weights, int width, int height) {
  const float inv_w = 1.0f / clip.w;
  const glm::vec3 screen = screen_from_clip(clip, inv_w, width, height);
  return {screen.x, screen.y, screen.z, inv_w, weights.y * inv_w, weights.z * inv_w};
}

SnappedVertex snap(const ScreenVertex& v, int width, int height) {
  return {snap_to_subpixel(v.x, width), snap_to_subpixel(v.y, height), v.z, v.inv_w, v.b1_w, v.b2_w};
}

class Binner {
 public:
  Binner(const SetupInput& in, SetupChunk& out) : in_(in), out_(out) {}

  // A screen triangle that survived the cheap tests, clockwise on screen, with its pixel bounds.
  struct Shape {
    std::int32_t X[3], Y[3];
    std::int64_t area;  // twice the signed area of the clockwise triangle in 1/256-pixel units: positive
    bool flipped;       // X[1], Y[1] and X[2], Y[2] were swapped to make it clockwise
    bool front;
    int px0, py0, px1, py1;
    std::uint32_t bounds_fraction;  // TriangleSetup::bounds_fraction, multisampled
  };

  // The tests that need only snapped positions: zero area, facing, culling, pixel centres inside the bounds and,
  // when the bounds hold at most four, whether the triangle covers any of them. Most triangles of a dense mesh
  // fail one of these, so they run before anything else of the triangle is read.
  // `facing` is +1 (front), -1 (back) when the caller knows it from the whole clipped polygon, or 0 to take it
  // from this triangle. Counts the triangle as culled and returns false when it fails.
  [[gnu::always_inline]] bool classify(const std::int32_t x[3], const std::int32_t y[3], int facing, bool cull,
                                       Shape& s) {
    // Twice the signed area in 1/256-pixel units; with y down, counter-clockwise in window space is negative.
    const std::int64_t area = std::int64_t{x[1] - x[0]} * (y[2] - y[0]) - std::int64_t{x[2] - x[0]} * (y[1] - y[0]);
    s.front = facing != 0 ? facing > 0 : area < 0;
    const bool sliver = facing != 0 && (area < 0) != s.front;  // a clipped polygon's piece flipped by snapping
    if (area == 0 || sliver ||
        (cull && ((in_.cull == CullMode::back && !s.front) || (in_.cull == CullMode::front && s.front)))) {
      ++out_.culled;
      return false;
    }
    const SamplePattern& pattern = sample_pattern(in_.samples);
    if (!pixel_bounds(std::min({x[0], x[1], x[2]}), std::min({y[0], y[1], y[2]}), std::max({x[0], x[1], x[2]}),
                      std::max({y[0], y[1], y[2]}), s)) {
      ++out_.culled;
      return false;
    }
    // Rasterize every triangle clockwise on screen, so that inside is positive for all edges.
    s.flipped = area < 0;
    s.area = s.flipped ? -area : area;
    const int second = s.flipped ? 2 : 1, third = s.flipped ? 1 : 2;
    s.X[0] = x[0], s.X[1] = x[second], s.X[2] = x[third];
    s.Y[0] = y[0], s.Y[1] = y[second], s.Y[2] = y[third];
    // Dense meshes make many triangles whose bounds hold a pixel or two, and many of those cover none of their
    // centres (or samples): test those now rather than set up a triangle that covers nothing and rasterize it.
    if ((s.px1 - s.px0 + 1) * (s.py1 - s.py0 + 1) <= 4 && !covers_a_sample(s, pattern)) {
      ++out_.culled;
      return false;
    }
    return true;
  }

  // The pixels whose centres (i + 0.5) * 256 (or, multisampled, any of whose samples) lie within the snapped extremes
  // [min_x, max_x] x [min_y, max_y], clamped to the target, into s.px0 .. s.py1 (and s.bounds_fraction); false when
  // none does.
  [[gnu::always_inline]] bool pixel_bounds(std::int32_t min_x, std::int32_t min_y, std::int32_t max_x,
                                           std::int32_t max_y, Shape& s) const {
    const SamplePattern& pattern = sample_pattern(in_.samples);
    const int lo = pattern.lo, hi = pattern.hi;
    const auto first = static_cast<int>(floor_div_subpixel(min_x - hi + kSubpixelScale - 1));
    const auto top = static_cast<int>(floor_div_subpixel(min_y - hi + kSubpixelScale - 1));
    const auto last = static_cast<int>(floor_div_subpixel(max_x - lo));
    const auto bottom = static_cast<int>(floor_div_subpixel(max_y - lo));
    s.px0 = std::max(0, first);
    s.py0 = std::max(0, top);
    s.px1 = std::min(in_.width - 1, last);
    s.py1 = std::min(in_.height - 1, bottom);
    if (in_.multisample())
      s.bounds_fraction =
          bounds_fractions(min_x, min_y, max_x, max_y, first, top, last, bottom, in_.width - 1, in_.height - 1);
    return s.px0 <= s.px1 && s.py0 <= s.py1;
  }

  // A screen-aligned rectangle [x0, x1) x [y0, y1) (1/256 pixel) at one depth and 1/w, each corner carrying vertex
  // `slot`, set up as one primitive whose edges pass everywhere: its pixel bounds are then exactly its coverage, and
  // with multisampling each sample's bounds are (at_sample). A centre on the left or top side is inside, one on the
  // right or bottom side outside, as the fill rule treats a rectangle split into two triangles.
  void rectangle(std::int32_t x0, std::int32_t y0, std::int32_t x1, std::int32_t y1, float z, float inv_w,
                 std::uint32_t slot, std::uint32_t primitive) {
    Shape s{};
    if (x1 <= x0 || y1 <= y0 || !pixel_bounds(x0, y0, x1 - 1, y1 - 1, s)) {
      ++out_.culled;
      return;
    }
    const auto index = static_cast<std::uint32_t>(out_.triangles.size());
    TriangleSetup& t = out_.triangles.emplace_back();
    for (int k = 0; k < 3; ++k) {
      t.edge[k] = {0, 0, 0};
      t.edge_fraction[k] = 0;
    }
    t.min_x = static_cast<std::int16_t>(s.px0);
    t.min_y = static_cast<std::int16_t>(s.py0);
    t.max_x = static_cast<std::int16_t>(s.px1);
    t.max_y = static_cast<std::int16_t>(s.py1);
    if (in_.multisample()) t.bounds_fraction = s.bounds_fraction;
    t.origin_x = static_cast<float>(x0) / kSubpixelScale;
    t.origin_y = static_cast<float>(y0) / kSubpixelScale;
    t.depth = {z, 0.0f, 0.0f};
    t.inv_w = {inv_w, 0.0f, 0.0f};
    t.b1_over_w = t.b2_over_w = {0.0f, 0.0f, 0.0f};  // every pixel takes vertex 0's varyings
    for (std::uint32_t& v : t.vertex) v = slot;
    t.primitive = primitive;
    t.front_facing = true;
    bin(t, index);
  }

  // Sets up one screen triangle given in the source winding.
  void triangle(const SnappedVertex v[3], const std::uint32_t vertex[3], std::uint32_t primitive, int facing,
                bool cull) {
    const std::int32_t x[3] = {v[0].x, v[1].x, v[2].x}, y[3] = {v[0].y, v[1].y, v[2].y};
    Shape s;
    if (!classify(x, y, facing, cull, s)) return;
    CornerValues c;
    for (int k = 0; k < 3; ++k) {
      const SnappedVertex& corner = v[clockwise_source(s, k)];
      c.value[0][k] = corner.z, c.value[1][k] = corner.inv_w, c.value[2][k] = corner.b1_w, c.value[3][k] = corner.b2_w;
    }
    set_up(s, c, vertex, primitive);
  }

  // A triangle of projected vertices (none outside the frustum) that passed classify; corner in the source winding.
  // Reads the corners' depth and 1/w from the vertex stage's output, long since stored, rather than from copies
  // just made: loading values that are still in the store buffer through wider loads stalls.
  [[gnu::noinline]] void set_up_projected(const Shape& s, const ProjectedVertex* const corner[3],
                                          const std::uint32_t vertex[3], std::uint32_t primitive) {
    CornerValues c;
    for (int k = 0; k < 3; ++k) {
      const int source = clockwise_source(s, k);
      const float inv_w = corner[source]->inv_w;
      c.value[0][k] = corner[source]->z, c.value[1][k] = inv_w;
      c.value[2][k] = source == 1 ? inv_w : 0.0f, c.value[3][k] = source == 2 ? inv_w : 0.0f;
    }
    set_up(s, c, vertex, primitive);
  }

  // A triangle the culling pass accepted, from that pass's lane i and setup_accepted_lanes's edges and planes.
  void set_up_lane(const CullLanes& cull, const SetupLanes& lanes, int i, const std::uint32_t vertex[3],
                   std::uint32_t primitive) {
    const auto index = static_cast<std::uint32_t>(out_.triangles.size());
    TriangleSetup& t = out_.triangles.emplace_back();
    for (int k = 0; k < 3; ++k) {
      t.edge[k] = {lanes.edge_a[k][i], lanes.edge_b[k][i], lanes.edge_q[k][i]};
      t.edge_fraction[k] = lanes.edge_fraction[k][i];
    }
    t.min_x = static_cast<std::int16_t>(cull.px0[i]);
    t.min_y = static_cast<std::int16_t>(cull.py0[i]);
    t.max_x = static_cast<std::int16_t>(cull.px1[i]);
    t.max_y = static_cast<std::int16_t>(cull.py1[i]);
    if (in_.multisample()) t.bounds_fraction = cull.bounds_fraction[i];
    t.origin_x = lanes.origin_x[i];
    t.origin_y = lanes.origin_y[i];
    Plane* const planes[4] = {&t.depth, &t.inv_w, &t.b1_over_w, &t.b2_over_w};
    for (int p = 0; p < 4; ++p) *planes[p] = {lanes.plane[p][0][i], lanes.plane[p][1][i], lanes.plane[p][2][i]};
    for (int k = 0; k < 3; ++k) t.vertex[k] = vertex[k];
    t.primitive = primitive;
    t.front_facing = cull.front[i] != 0;
    bin(t, index);
  }

 private:
  // Whether any sample of a pixel within the bounds (its centre, with one sample) is inside all three clockwise
  // edges, the fill rule included: the test rasterization makes of it (at_sample).
  static bool covers_a_sample(const Shape& s, const SamplePattern& pattern) {
    const std::int64_t half = kSubpixelScale / 2;
    for (int py = s.py0; py <= s.py1; ++py)
      for (int px = s.px0; px <= s.px1; ++px)
        for (int n = 0; n < pattern.count; ++n) {
          const std::int64_t cx = std::int64_t{px} * kSubpixelScale + half + pattern.offset[n].x;
          const std::int64_t cy = std::int64_t{py} * kSubpixelScale + half + pattern.offset[n].y;
          bool inside = true;
          for (int k = 0; k < 3; ++k) {
            const int a = k, b = (k + 1) % 3;
            inside &= edge_function<std::int64_t>(std::int64_t{s.X[b]} - s.X[a], std::int64_t{s.Y[b]} - s.Y[a], s.X[a],
                                                  s.Y[a], cx, cy) >= 0;
          }
          if (inside) return true;
        }
    return false;
  }

  // The source corner at clockwise position k.
  static int clockwise_source(const Shape& s, int k) { return s.flipped && k != 0 ? 3 - k : k; }

  // Edges, bounds, planes and bins of a triangle that passed classify, with its corner values in clockwise order.
  [[gnu::always_inline]] void set_up(const Shape& s, const CornerValues& c, const std::uint32_t vertex[3],
                                     std::uint32_t primitive) {
    const std::int32_t* X = s.X;
    const std::int32_t* Y = s.Y;
    // Written in place, field by field (see DefaultInitAllocator): a copy from the stack would reload fields
    // still in the store buffer through wider loads, which stalls.
    const auto index = static_cast<std::uint32_t>(out_.triangles.size());
    TriangleSetup& t = out_.triangles.emplace_back();
    for (int k = 0; k < 3; ++k) {
      const int a = k, b = (k + 1) % 3;
      t.edge[k] = make_edge(std::int64_t{X[b]} - X[a], std::int64_t{Y[b]} - Y[a], X[a], Y[a]);
      t.edge_fraction[k] = edge_fraction(std::int64_t{X[b]} - X[a], std::int64_t{Y[b]} - Y[a], X[a], Y[a]);
    }
    t.min_x = static_cast<std::int16_t>(s.px0);
    t.min_y = static_cast<std::int16_t>(s.py0);
    t.max_x = static_cast<std::int16_t>(s.px1);
    t.max_y = static_cast<std::int16_t>(s.py1);
    if (in_.multisample()) t.bounds_fraction = s.bounds_fraction;

    // Interpolation planes from the snapped positions, so that they agree with coverage. The determinant in
    // pixels is the area classify computed, exactly.
    const double scale = 1.0 / kSubpixelScale;
    const double dx1 = (X[1] - X[0]) * scale, dy1 = (Y[1] - Y[0]) * scale;
    const double dx2 = (X[2] - X[0]) * scale, dy2 = (Y[2] - Y[0]) * scale;
    const double inv_det = double{kSubpixelScale * kSubpixelScale} / static_cast<double>(s.area);
    t.origin_x = static_cast<float>(X[0] * scale);
    t.origin_y = static_cast<float>(Y[0] * scale);
    Plane* const planes[4] = {&t.depth, &t.inv_w, &t.b1_over_w, &t.b2_over_w};
    for (int p = 0; p < 4; ++p)
      *planes[p] = make_plane(c.value[p][0], c.value[p][1], c.value[p][2], dx1, dy1, dx2, dy2, inv_det);
    for (int k = 0; k < 3; ++k) t.vertex[k] = vertex[k];
    t.primitive = primitive;
    t.front_facing = s.front;
    bin(t, index);
  }

  void bin(const TriangleSetup& t, std::uint32_t index) {
    const int tx0 = t.min_x / kTileSize, tx1 = t.max_x / kTileSize;
    const int ty0 = t.min_y / kTileSize, ty1 = t.max_y / kTileSize;
    const bool single = tx0 == tx1 && ty0 == ty1;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx)
        if (single || touches_tile(t, tx * kTileSize, ty * kTileSize, in_.multisample()))
          out_.add(static_cast<std::uint32_t>(ty * in_.tiles_x + tx), index);
  }

  // False when one edge has every pixel centre (multisampled: every sample) of the tile outside: large triangles
  // skip the tiles their bounding box covers but they do not. Samples lie within half a pixel of the centre.
  static bool touches_tile(const TriangleSetup& t, int x, int y, bool multisample) {
    for (const Edge& e : t.edge) {
      const std::int64_t corner = std::int64_t{e.a} * x + std::int64_t{e.b} * y + e.q;
      const std::int64_t slack = multisample ? (std::abs(std::int64_t{e.a}) + std::abs(std::int64_t{e.b})) / 2 + 1 : 0;
      const std::int64_t reach = std::max<std::int64_t>(0, std::int64_t{e.a} * (kTileSize - 1)) +
                                 std::max<std::int64_t>(0, std::int64_t{e.b} * (kTileSize - 1)) + slack;
      if (corner + reach < 0) return false;
    }
    return true;
  }

  const SetupInput& in_;
  SetupChunk& out_;
};

}  // namespace

// A pass over the batch's indices ahead of setup, so it should run at memory speed: plain min/max loops that the
// vectoriser turns into unsigned min/max instructions, which need SSE4.1 or later, hence the clones.
VertexRange setup_vertex_range(std::span<const std::uint32_t> indices, std::size_t per_primitive,
                               std::size_t vertex_count, std::size_t first, std::size_t count) {
  return at_cpu_level([&]() __attribute__((always_inline)) {
    const std::uint32_t* index = indices.data() + first * per_primitive;
    const std::size_t total = count * per_primitive;
    const std::uint32_t limit = static_cast<std::uint32_t>(std::min<std::size_t>(vertex_count, 0xffffffffu));
    std::uint32_t lowest = 0xffffffffu, highest = 0;
    for (std::size_t i = 0; i < total; ++i) {
      const std::uint32_t v = index[i];
      const std::uint32_t valid = 0u - static_cast<std::uint32_t>(v < limit);  // all ones or zero, no branch
      lowest = std::min(lowest, v | ~valid);
      highest = std::max(highest, v & valid);
    }
    // A valid index is below 0xffffffff, so lowest > highest means there was none.
    return lowest <= highest ? VertexRange{lowest, std::size_t{highest} + 1} : VertexRange{};
  });
}

namespace {

// A triangle's vertices within the shaded range (set-up triangles name them so: rasterization finds their varyings
// there) and their projected corners.
struct Corners {
  std::uint32_t slot[3];
  const ProjectedVertex* corner[3];
};
Corners corners_of(const SetupInput& in, const std::uint32_t source[3]) {
  Corners c;
  for (int k = 0; k < 3; ++k) {
    c.slot[k] = static_cast<std::uint32_t>(source[k] - in.vertex_first);
    c.corner[k] = &in.projected[c.slot[k]];
  }
  return c;
}

// One triangle, in full: clipping when it crosses the frustum, culling, set-up and binning.
[[gnu::always_inline]] inline void setup_triangle(const SetupInput& in, SetupChunk& out, Binner& binner,
                                                  std::size_t i) {
  const bool culling = in.cull != CullMode::none;
  const std::size_t tri = in.order ? in.order[i] : i;
  const std::uint32_t source[3] = {in.indices[3 * tri], in.indices[3 * tri + 1], in.indices[3 * tri + 2]};
  if (source[0] >= in.vertex_count || source[1] >= in.vertex_count || source[2] >= in.vertex_count) {
    ++out.invalid;
    return;
  }
  const auto [slot, corner] = corners_of(in, source);
  const auto primitive = static_cast<std::uint32_t>(tri);
  const std::uint32_t any_outside = corner[0]->outcode | corner[1]->outcode | corner[2]->outcode;
  if (any_outside == 0) {
    const std::int32_t x[3] = {corner[0]->x, corner[1]->x, corner[2]->x};
    const std::int32_t y[3] = {corner[0]->y, corner[1]->y, corner[2]->y};
    Binner::Shape shape;
    if (binner.classify(x, y, 0, culling, shape)) binner.set_up_projected(shape, corner, slot, primitive);
    return;
  }
  if ((corner[0]->outcode & corner[1]->outcode & corner[2]->outcode) || (any_outside & kNonFinite)) {
    ++out.culled;
    return;
  }
  glm::vec4 clip[3];
  for (int k = 0; k < 3; ++k) clip[k] = in.clip ? in.clip[slot[k]] : in.clip_position(in.clip_source, source[k]);
  ClipVertex polygon[kMaxClipVertices];
  const int n = clip_triangle(clip, polygon);
  ++out.clipped;
  if (n < 3) return;
  ScreenVertex v[kMaxClipVertices];
  double area = 0.0;
  for (int k = 0; k < n; ++k) v[k] = to_screen(polygon[k].position, polygon[k].weights, in.width, in.height);
  for (int k = 1; k + 1 < n; ++k)
    area += double{v[k].x - v[0].x} * (v[k + 1].y - v[0].y) - double{v[k + 1].x - v[0].x} * (v[k].y - v[0].y);
  if (area == 0.0) {
    ++out.culled;
    return;
  }
  const int facing = area < 0.0 ? 1 : -1;
  if (culling && ((in.cull == CullMode::back && facing < 0) || (in.cull == CullMode::front && facing > 0))) {
    ++out.culled;
    return;
  }
  for (int k = 1; k + 1 < n; ++k) {
    SnappedVertex fan[3] = {snap(v[0], in.width, in.height), snap(v[k], in.width, in.height),
                            snap(v[k + 1], in.width, in.height)};
    binner.triangle(fan, slot, primitive, facing, false);
  }
}

// A triangle the culling pass accepted (see CullLanes), with its edges and planes already computed in lanes.
[[gnu::always_inline]] inline void set_up_accepted(const SetupInput& in, Binner& binner, const CullLanes& cull,
                                                   const SetupLanes& lanes, int lane, std::size_t tri) {
  std::uint32_t slot[3];
  for (int k = 0; k < 3; ++k) slot[k] = static_cast<std::uint32_t>(in.indices[3 * tri + k] - in.vertex_first);
  binner.set_up_lane(cull, lanes, lane, slot, static_cast<std::uint32_t>(tri));
}

}  // namespace

void setup_triangles(const SetupInput& in, SetupChunk& out) {
  Binner binner(in, out);
  const std::size_t end = in.first + in.count;
  std::size_t i = in.first;
  // Whole runs of kCullLanes triangles in index order go through the branch-free culling pass first.
  CullLanes lanes;
  SetupLanes set_up;
  if (!in.order)
    for (; i + kCullLanes <= end; i += kCullLanes) {
      setup_cull_lanes(in, i, lanes);
      if (lanes.accepted) setup_accepted_lanes(in, i, lanes, set_up);
      std::size_t kept = 0;
      for (std::uint32_t bits = lanes.keep; bits; bits &= bits - 1, ++kept) {
        const int lane = std::countr_zero(bits);
        if (lanes.accepted >> lane & 1u)
          set_up_accepted(in, binner, lanes, set_up, lane, i + static_cast<std::size_t>(lane));
        else setup_triangle(in, out, binner, i + static_cast<std::size_t>(lane));
      }
      out.culled += static_cast<std::size_t>(kCullLanes) - kept;
    }
  for (; i < end; ++i) setup_triangle(in, out, binner, i);
}

void setup_lines(const SetupInput& in, SetupChunk& out) {
  Binner binner(in, out);
  const float half_width = std::max(in.line_width, 0.01f) * 0.5f;
  for (std::size_t p = in.first; p < in.first + in.count; ++p) {
    const std::uint32_t a = in.indices[2 * p], b = in.indices[2 * p + 1];
    if (a >= in.vertex_count || b >= in.vertex_count) {
      ++out.invalid;
      continue;
    }
    const glm::vec4 clip_a = in.clip[a - in.vertex_first], clip_b = in.clip[b - in.vertex_first];
    float t0, t1;
    if (!clip_line(clip_a, clip_b, t0, t1)) {
      ++out.culled;
      continue;
    }
    const glm::vec4 delta = clip_b - clip_a;
    const ScreenVertex s0 = to_screen(clip_a + t0 * delta, glm::vec3(1.0f - t0, t0, 0.0f), in.width, in.height);
    const ScreenVertex s1 = to_screen(clip_a + t1 * delta, glm::vec3(1.0f - t1, t1, 0.0f), in.width, in.height);
    // A line is a screen-aligned rectangle half_width to each side and beyond each end (square caps), drawn as two
    // triangles that share their diagonal, so the fill rule covers each pixel once.
    float dx = s1.x - s0.x, dy = s1.y - s0.y;
    const float length = std::sqrt(dx * dx + dy * dy);
    if (!(length > 0.0f)) {
      dx = 1.0f;
      dy = 0.0f;
    } else {
      dx /= length;
      dy /= length;
    }
    const float ax = dx * half_width, ay = dy * half_width;  // along the line
    const float nx = -ay, ny = ax;                           // across it
    auto corner = [](ScreenVertex s, float ox, float oy) {
      s.x += ox;
      s.y += oy;
      return s;
    };
    const auto slot_a = static_cast<std::uint32_t>(a - in.vertex_first),
               slot_b = static_cast<std::uint32_t>(b - in.vertex_first);
    const std::uint32_t vertex[3] = {slot_a, slot_b, slot_b};
    const auto primitive = static_cast<std::uint32_t>(p);
    ScreenVertex first[3] = {corner(s0, -ax + nx, -ay + ny), corner(s1, ax + nx, ay + ny),
                             corner(s1, ax - nx, ay - ny)};
    ScreenVertex second[3] = {corner(s0, -ax + nx, -ay + ny), corner(s1, ax - nx, ay - ny),
                              corner(s0, -ax - nx, -ay - ny)};
    for (ScreenVertex* quad_half : {first, second}) {
      SnappedVertex snapped[3] = {snap(quad_half[0], in.width, in.height), snap(quad_half[1], in.width, in.height),
                                  snap(quad_half[2], in.width, in.height)};
      binner.triangle(snapped, vertex, primitive, 0, false);
    }
  }
}

int disc_sides(float diameter) {
  // A side of a regular n-gon inscribed in a circle of radius r lies r (1 - cos(pi / n)) inside the circle at most.
  const float r = diameter * 0.5f;
  if (!(r > 0.1f)) return 8;
  const float sides = std::ceil(std::numbers::pi_v<float> / std::acos(1.0f - 0.1f / r));
  return static_cast<int>(std::clamp(sides, 8.0f, static_cast<float>(kMaxDiscSides)));
}

// The corners of a point's square or disc around its centre, counter-clockwise on screen (y down), for a size in
// pixels; kept from one point to the next while the size stays the same (always, but for points sized by depth).
struct PointCorners {
  float size = -1.0f;
  int sides = 0;
  float x[kMaxDiscSides], y[kMaxDiscSides];

  void set(float point_size, PointShape shape) {
    if (point_size == size) return;
    size = point_size;
    const float half = point_size * 0.5f;
    sides = shape == PointShape::disc ? disc_sides(point_size) : 4;
    for (int k = 0; k < sides; ++k) {
      if (shape == PointShape::disc) {
        const float angle = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) / static_cast<float>(sides);
        x[k] = half * std::cos(angle);
        y[k] = -half * std::sin(angle);
      } else {
        x[k] = k == 0 || k == 3 ? -half : half;
        y[k] = k < 2 ? -half : half;
      }
    }
  }
};

void setup_points(const SetupInput& in, SetupChunk& out) {
  Binner binner(in, out);
  const bool by_depth = in.point_size_per_w > 0.0f;
  PointCorners corners;
  if (!by_depth) corners.set(std::max(in.point_size, 0.01f), in.point_shape);
  for (std::size_t p = in.first; p < in.first + in.count; ++p) {
    const std::uint32_t v = in.indices[p];
    if (v >= in.vertex_count) {
      ++out.invalid;
      continue;
    }
    // As OpenGL clips a point: by its position alone, so a point partly off screen keeps its pixels on screen.
    const glm::vec4 clip = in.clip[v - in.vertex_first];
    if (outcode(clip) != 0) {
      ++out.culled;
      continue;
    }
    if (by_depth) corners.set(std::clamp(in.point_size_per_w / clip.w, kMinScaledPointSize, kMaxPointSize), in.point_shape);
    const ScreenVertex centre = to_screen(clip, glm::vec3(1.0f, 0.0f, 0.0f), in.width, in.height);
    const auto corner = [&](int k) {
      ScreenVertex s = centre;
      s.x += corners.x[k];
      s.y += corners.y[k];
      return snap(s, in.width, in.height);
    };
    const auto slot = static_cast<std::uint32_t>(v - in.vertex_first);
    const auto primitive = static_cast<std::uint32_t>(p);
    if (in.point_shape == PointShape::square) {
      const SnappedVertex top_left = corner(0), bottom_right = corner(2);
      binner.rectangle(top_left.x, top_left.y, bottom_right.x, bottom_right.y, centre.z, centre.inv_w, slot, primitive);
      continue;
    }
    const std::uint32_t vertex[3] = {slot, slot, slot};
    // A fan from corner 0: neighbouring triangles share their edges, so the fill rule covers each pixel once.
    for (int k = 1; k + 1 < corners.sides; ++k) {
      SnappedVertex fan[3] = {corner(0), corner(k), corner(k + 1)};
      binner.triangle(fan, vertex, primitive, 0, false);
    }
  }
}

void setup_depth_keys(const glm::vec4* clip, std::size_t vertex_count, std::span<const std::uint32_t> indices,
                      std::span<float> keys) {
  for (std::size_t t = 0; t < keys.size(); ++t) {
    float sum = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = indices[3 * t + k];
      if (i >= vertex_count) continue;
      const glm::vec4& c = clip[i];
      sum += c.w > kMinW ? c.z / c.w : 1.0f;  // corners at or behind the eye sort as far as possible
    }
    keys[t] = std::isfinite(sum) ? sum : 3.0f;
  }
}

}  // namespace facet::detail
