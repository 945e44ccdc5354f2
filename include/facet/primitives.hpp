// primitives.hpp - procedural meshes: a per-face-coloured cube, a colour-swept torus, a UV sphere, a pentagon.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "facet/mesh.hpp"

namespace facet {

// The cube of "Barebones 3D rendering with WebGL": side 2 centred at the origin, its 12 triangles in that post's
// order (front +z red, right +x green, back -z blue, left -x yellow, +y magenta, -y cyan; each face's quad
// c0 c1 c2 c3 as (c0 c1 c2), (c0 c2 c3)). 24 vertices (4 per face) with the face normal, uvs 0..1 across the face
// (u to the right and v up, seen from outside), per-vertex colours equal to the face colour, and face_colors.
Mesh make_cube();

// The post's own vertex buffer for that cube: 36 non-indexed vertices of 6 floats, position then rgb (stride 24
// bytes, offsets 0 and 12), ready for mesh_from_interleaved.
std::vector<float> colored_cube_vertex_data();

// Torus around the z axis: the tube's centre circle of radius major_radius lies in the z = 0 plane, the tube has
// radius minor_radius. Ring i = 0..major_segments sits at angle u = 2*pi*i/major_segments around z, and vertex j =
// 0..minor_segments at angle v = 2*pi*j/minor_segments around the tube, starting at the outer equator and going
// towards +z. The last ring and column repeat the first ones' positions and normals bit for bit, with their own uv
// and colour. uv = (i / major_segments, j / minor_segments). Colour sweeps from blue (u = 0) to red (u = 2*pi):
// rgb = (t, 0, 1 - t) with t = i / major_segments, like the torus pictured in "Barebones 3D rendering with WebGL".
// Throws std::invalid_argument unless both radii are finite and positive and both segment counts are >= 3 (and small
// enough for 32-bit indices).
Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments);

// Unit UV sphere built exactly as BENCHMARK.md 8.1 (its N is stacks = slices): vertex i*(slices+1)+j for stack i =
// 0..stacks (i = 0 is the +y pole) and slice j = 0..slices, theta = float(pi)*i/stacks, phi = 2*float(pi)*j/slices,
// normal = position = (sin theta cos phi, cos theta, sin theta sin phi), uv = (uv_repeat.x*j/slices,
// uv_repeat.y*i/stacks); the default (8, 4) is the benchmark's tiling, so make_uv_sphere(N, N) is bit-identical to
// scene sphere:N. 2*slices*(stacks-1) triangles. Throws std::invalid_argument unless stacks >= 2 and slices >= 3 (and
// small enough for 32-bit indices).
Mesh make_uv_sphere(int stacks, int slices, glm::vec2 uv_repeat = {8.0f, 4.0f});

// Regular pentagon of circumradius 1 in the z = 0 plane facing +z, first corner at +y, corners counter-clockwise,
// drawn as the triangle fan 0 1 2 3 4 (3 triangles). Corner colours red, yellow, green, blue, magenta; normal +z;
// uv = (0.5 + 0.5x, 0.5 + 0.5y).
Mesh make_pentagon();

}  // namespace facet
