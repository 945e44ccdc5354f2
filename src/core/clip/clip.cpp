// clip.cpp - Sutherland-Hodgman clipping in homogeneous clip space (before the w-divide).
#include "core/clip/clip.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace facet::detail {
namespace {

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

}  // namespace

int clip_triangle(const glm::vec4 (&clip)[3], ClipVertex (&out)[kMaxClipVertices]) {
  std::uint32_t any_outside = 0, all_outside = ~0u;
  for (const glm::vec4& v : clip) {
    const std::uint32_t code = outcode(v);
    any_outside |= code;
    all_outside &= code;
  }
  if (all_outside || (any_outside & kNonFinite)) return 0;

  ClipVertex buffer[kMaxClipVertices];
  ClipVertex* in = out;
  ClipVertex* next = buffer;
  int count = 3;
  for (int k = 0; k < 3; ++k) in[k] = {clip[k], glm::vec3(k == 0, k == 1, k == 2)};

  for (int plane = 0; plane < kClipPlanes && count > 0; ++plane) {
    if (!(any_outside & (1u << plane))) continue;
    int written = 0;
    for (int k = 0; k < count; ++k) {
      const ClipVertex& a = in[k];
      const ClipVertex& b = in[(k + 1) % count];
      const float da = plane_distance(a.position, plane), db = plane_distance(b.position, plane);
      if (da >= 0.0f) next[written++] = a;
      if ((da >= 0.0f) != (db >= 0.0f)) {
        // Interpolate from the inside end: the two triangles sharing an edge walk it in opposite directions and
        // must still produce bit-identical points, or the shared edge cracks.
        const ClipVertex& inside = da >= 0.0f ? a : b;
        const ClipVertex& outside = da >= 0.0f ? b : a;
        const float di = da >= 0.0f ? da : db, dout = da >= 0.0f ? db : da;
        const float t = di / (di - dout);
        next[written++] = {inside.position + t * (outside.position - inside.position),
                           inside.weights + t * (outside.weights - inside.weights)};
      }
    }
    count = written;
    std::swap(in, next);
  }
  if (in != out)
    for (int k = 0; k < count; ++k) out[k] = in[k];
  return count >= 3 ? count : 0;
}

bool clip_line(const glm::vec4& a, const glm::vec4& b, float& t0, float& t1) {
  if (!finite(a) || !finite(b)) return false;
  t0 = 0.0f;
  t1 = 1.0f;
  for (int plane = 0; plane < kClipPlanes; ++plane) {
    const float da = plane_distance(a, plane), db = plane_distance(b, plane);
    if (da < 0.0f && db < 0.0f) return false;
    if (da < 0.0f) t0 = std::max(t0, da / (da - db));
    if (db < 0.0f) t1 = std::min(t1, da / (da - db));
  }
  return t0 < t1;
}

}  // namespace facet::detail
