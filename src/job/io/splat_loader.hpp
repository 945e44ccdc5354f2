// splat_loader.hpp - Gaussian splat scenes: the 3D Gaussian Splatting paper's PLY layout and the .splat format.
#pragma once

#include <string>
#include <string_view>

#include "facet/mesh.hpp"
#include "job/io/ply_header.hpp"

namespace facet {

// Whether a vertex element has the paper's properties (f_dc_0, opacity, scale_0, rot_0): a splat scene, not a cloud.
bool is_splat_layout(const ply::Element& vertex);

// The Gaussians of a splat PLY (ASCII or binary, any scalar property types): x y z, f_dc_0..2, f_rest_* (0, 9, 24
// or 45 of them: spherical harmonics of degree 0 to 3, channel by channel), opacity, scale_0..2 and rot_0..3 (w x y
// z), with the paper's activations (sigmoid opacity, exponential scales, normalised rotations); other properties are
// skipped. Gaussians with a non-finite value, a zero rotation or a scale beyond a float are skipped with a warning.
// The mesh holds the Gaussians (Mesh::splats) and their centres as positions. Throws InputError(source, ...).
Mesh load_splat_ply(std::string_view bytes, const ply::Header& header, const ply::Element& vertex,
                    const std::string& source);

// A .splat file (the web viewers' compact format, converted from the paper's PLY): 32 bytes per Gaussian, x y z and
// three linear scales as little-endian float32, then r g b (the displayed colour) and alpha (the opacity) as bytes,
// then the rotation w x y z as bytes q * 128 + 128. Degree 0. Gaussians with a non-finite or negative value or a
// zero rotation are skipped with a warning. Throws InputError(source, ...), for one whose size is not a multiple of
// 32 bytes too.
Mesh load_splat(std::string_view bytes, const std::string& source);

}  // namespace facet
