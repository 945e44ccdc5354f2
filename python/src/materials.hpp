// materials.hpp - the Python module's materials and textures: pyrender's MetallicRoughnessMaterial as a facet one.
#pragma once

#include <memory>
#include <string>

#include "arrays.hpp"
#include "facet/mesh.hpp"
#include "facet/texture.hpp"

namespace facet::python {

// An image H x W (x 1, 3 or 4), top row first (uint8, or floats in 0..1), as a mipmapped texture holding texels of
// `encoding`. Raises ValueError naming `name` for a wrong shape, dtype, size or value.
std::shared_ptr<const Texture> texture_of(py::handle image, const std::string& name, TexelEncoding encoding);

// The look of a mesh that names no material: the renderer's own default (white, the classic shadings' specular 0.4
// at shininess 32, a dielectric of roughness 0.5), single-sided as pyrender's default material is.
Material default_material();

// facet.MetallicRoughnessMaterial's description (its _core_dict()) as a Material: the linear base colour factor
// encoded as displayed as the glTF reader encodes it, emission kept linear, the textures decoded. Raises ValueError
// for a bad value, or for a texture on a mesh without uvs.
Material material_of(py::handle description, bool has_uvs);

// Back faces are culled per material, as pyrender culls them: glTF files say which materials are double-sided;
// the other formats have no such flag, and their surfaces are single-sided, as pyrender draws them. Gives the
// triangles without a material default_material() so that they are culled too.
void make_sides_explicit(Mesh& mesh, const std::string& format);

}  // namespace facet::python
