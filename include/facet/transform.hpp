// transform.hpp - model transforms (translate, scale, rotate), the gluLookAt view matrix and the normal matrix.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

// Conventions (OpenGL): column-major glm matrices applied to column vectors (p' = M * p), right-handed, angles in
// radians, positive angles rotate counter-clockwise when looking from the tip of the axis towards the origin.
// Matrices compose right to left: translate(t) * rotate_y(a) * scale(s) scales first, translates last.
// Every function throws std::invalid_argument on non-finite or degenerate input instead of returning NaNs.
namespace facet {

glm::mat4 translate(glm::vec3 offset);
glm::mat4 scale(glm::vec3 factors);  // zero factors are allowed (flattening); the result is then singular
glm::mat4 scale(float factor);

// Rotation about an axis through the origin (the axis need not be unit length, but must not be zero).
glm::mat4 rotate(float radians, glm::vec3 axis);
glm::mat4 rotate_x(float radians);  // y towards z
glm::mat4 rotate_y(float radians);  // z towards x
glm::mat4 rotate_z(float radians);  // x towards y

// gluLookAt: the view matrix (eye space from world space) of a camera at `eye` looking at `target`. Eye space is
// right-handed with the camera at the origin looking down -Z and `up` projected to +Y. Throws when eye == target,
// when `up` is zero or parallel to the view direction, or on non-finite input.
glm::mat4 look_at(glm::vec3 eye, glm::vec3 target, glm::vec3 up);

// Inverse transpose of the upper 3x3: transforms surface normals so they stay perpendicular to transformed
// tangents under non-uniform scale. Throws when the 3x3 part is singular or non-finite.
glm::mat3 normal_matrix(const glm::mat4& m);

}  // namespace facet
