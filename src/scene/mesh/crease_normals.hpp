// crease_normals.hpp - compute_crease_normals with the number of threads given, for tests that vary it.
#pragma once

#include "facet/mesh.hpp"

namespace facet::detail {

// compute_crease_normals on `parts` threads (1 or more) where it would choose by the mesh's size; the result is the
// same for any count.
void compute_crease_normals_in_parts(Mesh& mesh, float crease_angle_radians, int parts);

}  // namespace facet::detail
