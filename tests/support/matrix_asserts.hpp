// matrix_asserts.hpp - element-wise EXPECT_NEAR for glm vectors and matrices, shared by the math tests.
#pragma once

#include <gtest/gtest.h>

#include <glm/glm.hpp>

namespace facet::test {

inline void expect_vec_near(glm::vec3 a, glm::vec3 b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Reports the column and row of each differing element, the way OpenGL and WebGL code indexes matrices.
inline void expect_mat_near(const glm::mat4& a, const glm::mat4& b, float tol = 1e-5f) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "column " << c << " row " << r;
}

}  // namespace facet::test
