// render_state.hpp - per-draw fixed-function state: culling, depth test, blending and draw order.
#pragma once

namespace facet {

enum class CullMode { none, back, front };  // front faces are counter-clockwise in window space (y up)

enum class DepthFunc { never, less, equal, lequal, greater, notequal, gequal, always };

// alpha: rgb = src.rgb * a + dst.rgb * (1 - a), alpha = a + dst.a * (1 - a) with a = src.a (the "over" operator,
// glBlendFuncSeparate(SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ONE, ONE_MINUS_SRC_ALPHA)), so coverage accumulates.
enum class BlendMode { none, alpha };

// How draw_points draws a point: a screen-aligned square of point_size pixels a side, or a disc of that diameter.
enum class PointShape { square, disc };
inline constexpr float kMaxPointSize = 256.0f;  // pixels; what the scene and job layers accept
inline constexpr float kMinScaledPointSize = 1.0f / 64.0f;  // pixels: the least a point sized by depth takes

enum class DrawOrder {
  as_given,       // index order, as OpenGL draws
  // The painter's algorithm: triangles by mean NDC depth, farthest first, ties in index order (use with depth_test
  // off). Sorted per tile; consecutive draws in this order are sorted together, ties in draw order.
  back_to_front,
};

struct RenderState {
  CullMode cull = CullMode::back;
  bool depth_test = true;
  bool depth_write = true;
  DepthFunc depth_func = DepthFunc::less;
  BlendMode blend = BlendMode::none;
  bool color_write = true;
  DrawOrder order = DrawOrder::as_given;
  float depth_offset = 0.0f;  // added to window depth before the test, e.g. -1e-4 pulls outlines onto a surface
  float line_width = 1.0f;    // pixels, for draw_lines
  float point_size = 1.0f;    // pixels, for draw_points: a square's side or a disc's diameter
  PointShape point_shape = PointShape::square;
  // Above 0: each point's size is point_size_per_w / w pixels instead, w its clip-space w (a fixed size in world
  // units under a perspective projection, where w is the distance along the view axis), clamped to
  // kMinScaledPointSize..kMaxPointSize; point_size is then unused.
  float point_size_per_w = 0.0f;
  // Shade each pixel once, after the depth test has seen all of a draw's triangles (tile-based deferred shading).
  // Applies when the shader cannot discard and colour is written without blending; the image is identical either
  // way, only overdraw gets cheaper. false shades every passing fragment as its triangle is drawn.
  bool defer_shading = true;
};

}  // namespace facet
