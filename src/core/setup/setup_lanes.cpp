// setup_lanes.cpp - edges and interpolation planes of the triangles the culling pass accepted, 16 at once.
#include <cstdint>

#include "facet/detail/dispatch.hpp"
#include "core/setup/setup.hpp"

namespace facet::detail {

// Why lanes: a dense mesh sets up tens of thousands of small triangles per frame, and one at a time each costs
// some 250 instructions, mostly the four planes' double-precision products and the edges' 64-bit ones. The same
// operations in plain loops over the culling pass's 16 lanes vectorise in every dispatch clone, in the same IEEE
// arithmetic (no contraction, see CMakeLists.txt), so each lane is bit for bit what Binner::set_up computes
// (both call make_edge and make_plane). Lanes the pass did not accept are computed too, branch-free, and ignored:
// their corners are snapped values or zero (a corner outside the frustum), so no integer product overflows; a zero
// area gives infinite planes.
void setup_accepted_lanes(const SetupInput& in, std::size_t first, const CullLanes& cull, SetupLanes& out) {
  at_cpu_level([&]() __attribute__((always_inline)) {
    constexpr int N = kCullLanes;
    const std::uint32_t* index = in.indices.data() + 3 * first;
    // The corner values in clockwise order: a front face had its corners 1 and 2 swapped (see CullLanes::front).
    float z[3][N], inv_w[3][N];
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < 3; ++k) {
        const int source = cull.front[i] && k != 0 ? 3 - k : k;
        const ProjectedVertex& v = in.projected[index[3 * i + source] - in.vertex_first];
        z[k][i] = v.z, inv_w[k][i] = v.inv_w;
      }

    for (int i = 0; i < N; ++i) {
      const std::int64_t X[3] = {cull.x[0][i], cull.x[1][i], cull.x[2][i]};
      const std::int64_t Y[3] = {cull.y[0][i], cull.y[1][i], cull.y[2][i]};
      for (int k = 0; k < 3; ++k) {
        const int a = k, b = (k + 1) % 3;
        const Edge edge = make_edge(X[b] - X[a], Y[b] - Y[a], X[a], Y[a]);
        out.edge_a[k][i] = edge.a, out.edge_b[k][i] = edge.b, out.edge_q[k][i] = edge.q;
        out.edge_fraction[k][i] = edge_fraction(X[b] - X[a], Y[b] - Y[a], X[a], Y[a]);
      }
      const double scale = 1.0 / kSubpixelScale;
      const double dx1 = static_cast<double>(X[1] - X[0]) * scale, dy1 = static_cast<double>(Y[1] - Y[0]) * scale;
      const double dx2 = static_cast<double>(X[2] - X[0]) * scale, dy2 = static_cast<double>(Y[2] - Y[0]) * scale;
      const double inv_det = double{kSubpixelScale * kSubpixelScale} / static_cast<double>(cull.area[i]);
      out.origin_x[i] = static_cast<float>(static_cast<double>(X[0]) * scale);
      out.origin_y[i] = static_cast<float>(static_cast<double>(Y[0]) * scale);
      // The weight planes' values are 1/w at the source corner they weigh and 0 elsewhere.
      const auto plane = [&](int p, float f0, float f1, float f2) __attribute__((always_inline)) {
        const Plane result = make_plane(f0, f1, f2, dx1, dy1, dx2, dy2, inv_det);
        out.plane[p][0][i] = result.at_origin, out.plane[p][1][i] = result.ddx, out.plane[p][2][i] = result.ddy;
      };
      const bool front = cull.front[i] != 0;
      plane(0, z[0][i], z[1][i], z[2][i]);
      plane(1, inv_w[0][i], inv_w[1][i], inv_w[2][i]);
      // Source corner 1 sits at clockwise position 1, or 2 when front-facing; source corner 2 at the other.
      const float w1 = front ? inv_w[2][i] : inv_w[1][i], w2 = front ? inv_w[1][i] : inv_w[2][i];
      plane(2, 0.0f, front ? 0.0f : w1, front ? w1 : 0.0f);
      plane(3, 0.0f, front ? w2 : 0.0f, front ? 0.0f : w2);
    }
  });
}

}  // namespace facet::detail
