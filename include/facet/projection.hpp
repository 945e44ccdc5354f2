// projection.hpp - OpenGL projection matrices (perspective, frustum, ortho, oblique) and classical view presets.
#pragma once

#include <glm/mat4x4.hpp>

// Conventions (OpenGL): the projections map right-handed eye space (camera at the origin looking down -Z) to clip
// space, and after the divide by w to the NDC cube [-1,1]^3 with the near plane at z = -1 and the far plane at
// z = +1. `near` and `far` are distances along -Z, as in glFrustum/glOrtho/gluPerspective. Every function throws
// std::invalid_argument (message names the function and the bad parameter) on non-finite or degenerate input.
namespace facet {

// gluPerspective: symmetric frustum with vertical field of view fovy (0 < fovy < pi), aspect = width / height > 0,
// 0 < near < far.
glm::mat4 perspective(float fovy_radians, float aspect, float near, float far);

// glFrustum: the near-plane window [left,right] x [bottom,top] at distance near; left != right, bottom != top
// (a reversed pair mirrors the image, as in OpenGL), 0 < near < far.
glm::mat4 frustum(float left, float right, float bottom, float top, float near, float far);

// glOrtho: the box [left,right] x [bottom,top] x [-near,-far] in eye space; left != right, bottom != top,
// near < far. near may be zero or negative (planes behind the eye), as in OpenGL.
glm::mat4 ortho(float left, float right, float bottom, float top, float near, float far);

// Oblique parallel projection = ortho(l, r, b, t, n, f) * H, H the xy shear of the CIS367 lecture notes "Building
// models / Viewing" ("Oblique projection"): H(theta, phi) = [1 0 -cot(theta) 0; 0 1 -cot(phi) 0; 0 0 1 0; 0 0 0 1] with
// cot(theta) = depth_scale * cos(angle), cot(phi) = depth_scale * sin(angle). A point one unit further from the eye
// is drawn depth_scale units further along the receding direction at `angle` from +X (counter-clockwise, e.g.
// pi/4 for the usual up-and-right). depth_scale 1 = cavalier, 0.5 = cabinet, 0 = plain orthographic.
// The shear leaves the plane z = -pivot_distance in place; the default 0 is the lecture's matrix exactly (the
// eye plane is fixed, so objects at distance d move by depth_scale * d). Pass the distance of the object of
// interest to keep it where ortho alone would put it.
glm::mat4 oblique(float angle_radians, float depth_scale, float left, float right, float bottom, float top, float near,
                  float far, float pivot_distance = 0.0f);

// Axonometric presets: VIEW rotations (eye space from world space, no translation) to be placed between a
// look-at/translation and an ortho projection. World +Y stays vertical on screen in all three.
//   isometric: rotate_x(asin(tan 30deg) = 35.2644deg) * rotate_y(-45deg). The eye looks from direction (1,1,1)
//              (same rotation as the CIS367 lecture's lookAt((1,1,1), (0,0,0), (0,1,0))); all three axes are
//              foreshortened equally (sqrt(2/3) = 0.8165) and drawn 120 degrees apart, X and Z at -30 / -150 degrees.
//   dimetric:  rotate_x(30deg) * rotate_y(-45deg), the "2:1" dimetric of pixel art and games: X and Z are
//              foreshortened equally (0.7906), Y less (0.8660); X and Z are drawn at atan(1/2) = 26.565 degrees
//              below horizontal, i.e. two pixels across per pixel down.
//   trimetric: rotate_x(30deg) * rotate_y(-30deg): there is no single standard trimetric; this one gives three
//              distinct foreshortenings X 0.9014, Y 0.8660, Z 0.6614 (eye direction (0.433, 0.5, 0.75)).
glm::mat4 isometric_view();
glm::mat4 dimetric_view();
glm::mat4 trimetric_view();

// Orthographic multiview presets (third-angle projection, as in CAD drawings): VIEW rotations like the above.
//   front_view: identity. Viewer on +Z looking towards -Z; screen right = +X, screen up = +Y.
//   top_view:   rotate_x(+90deg) (plan). Viewer on +Y looking down -Y; screen right = +X, screen up = -Z
//               (the back of the object is at the top of the drawing, the front faces the bottom edge).
//   side_view:  rotate_y(-90deg) (right side elevation). Viewer on +X looking towards -X; screen right = -Z,
//               screen up = +Y (the front of the object faces the left edge, next to the front view).
glm::mat4 front_view();
glm::mat4 top_view();
glm::mat4 side_view();

}  // namespace facet
