"""mesh.py - pyrender's Mesh: primitives drawn together, made from arrays, trimesh objects, points or files."""
import copy

import numpy as np

from ._shared import BoxMeasures, name_property
from . import _facet
from .constants import GLTF
from .material import MetallicRoughnessMaterial, _material_description
from .primitive import CorePrimitive, Primitive

# The limits model files are read within by default, as `facet render` reads them (LoadOptions in the C++ library's
# model_io.hpp): files a model names are read only from inside its folder tree, at most 100 million triangles are
# placed, and textures up to 16384 texels a side are decoded.
DEFAULT_MAX_TRIANGLES = _facet.DEFAULT_MAX_TRIANGLES
DEFAULT_MAX_POINTS = _facet.DEFAULT_MAX_POINTS
DEFAULT_MAX_TEXTURE_SIZE = _facet.MAX_TEXTURE_SIZE


def _trimesh_default_material():
    """The material pyrender gives a trimesh without one of its own."""
    return MetallicRoughnessMaterial(alphaMode="BLEND", baseColorFactor=[0.3, 0.3, 0.3, 1.0], metallicFactor=0.2,
                                     roughnessFactor=0.8)


def _per_corner(values, faces, smooth):
    return values if smooth else values[faces].reshape(3 * len(faces), values.shape[1])


def _trimesh_look(tm, smooth, material):
    """(colours, uvs, material) from a trimesh's visual, by duck typing, as pyrender reads them: vertex or face
    colours (with a white BLEND material), or a texture's uvs and its PBR or simple (OBJ) material."""
    visual = getattr(tm, "visual", None)
    if visual is None or not getattr(visual, "defined", True):
        return None, None, material
    faces, kind = np.asarray(tm.faces), getattr(visual, "kind", None)
    colors = uvs = None
    if material is None and kind in ("vertex", "face"):
        if kind == "vertex":
            colors = _per_corner(np.asarray(visual.vertex_colors), faces, smooth)
        elif smooth:
            raise ValueError("from_trimesh: face colours need smooth=False (each face its own vertices)")
        else:
            colors = np.repeat(np.asarray(visual.face_colors), 3, axis=0)
        material = MetallicRoughnessMaterial(alphaMode="BLEND", baseColorFactor=[1.0, 1.0, 1.0, 1.0],
                                             metallicFactor=0.2, roughnessFactor=0.8)
    if kind == "texture":
        uv = getattr(visual, "uv", None)
        if uv is not None and len(uv):
            uvs = _per_corner(np.asarray(uv, dtype=np.float64), faces, smooth)
        if material is None:
            material = _material_of_visual(getattr(visual, "material", None))
    return colors, uvs, material


def _material_of_visual(mat):
    if mat is None or isinstance(mat, MetallicRoughnessMaterial):
        return mat
    if hasattr(mat, "baseColorFactor") or hasattr(mat, "metallicRoughnessTexture"):  # trimesh's PBRMaterial
        keys = ("normalTexture", "occlusionTexture", "emissiveTexture", "emissiveFactor", "baseColorFactor",
                "baseColorTexture", "metallicFactor", "roughnessFactor", "metallicRoughnessTexture", "alphaCutoff")
        values = {k: getattr(mat, k, None) for k in keys}
        return MetallicRoughnessMaterial(alphaMode="BLEND", doubleSided=bool(getattr(mat, "doubleSided", False)),
                                         **values)
    # trimesh's SimpleMaterial (an OBJ's MTL): its Phong exponent Ns turned into a roughness as pyrender turns it.
    glossiness = getattr(mat, "kwargs", {}).get("Ns", 1.0)
    if isinstance(glossiness, (list, tuple)):
        glossiness = float(glossiness[0])
    return MetallicRoughnessMaterial(alphaMode="BLEND", roughnessFactor=(2.0 / (float(glossiness) + 2.0)) ** 0.25,
                                     baseColorFactor=getattr(mat, "diffuse", None),
                                     baseColorTexture=getattr(mat, "image", None))


class Mesh(BoxMeasures):
    """Primitives drawn together, placed by one node, as pyrender's Mesh. Made from Primitives, from trimesh
    objects (from_trimesh), points (from_points), a model file (from_file) or plain arrays (from_arrays)."""

    def __init__(self, primitives, name=None, weights=None, is_visible=True):
        self.primitives, self.name, self.weights, self.is_visible = primitives, name, weights, is_visible

    name = name_property()

    @property
    def primitives(self):
        return self._primitives

    @primitives.setter
    def primitives(self, value):
        value = list(value)
        for p in value:
            if not isinstance(p, (Primitive, CorePrimitive)):
                raise TypeError(f"primitives: expected facet.Primitive objects, got {type(p).__name__}")
        self._primitives = value

    @property
    def bounds(self):
        """2 x 3: the box around every primitive (and instance); inf and -inf for a mesh without primitives."""
        out = np.array([[np.inf] * 3, [-np.inf] * 3])
        for p in self.primitives:
            b = p.bounds
            out = np.array([np.minimum(out[0], b[0]), np.maximum(out[1], b[1])])
        return out

    @property
    def is_transparent(self):
        return any(p.is_transparent for p in self.primitives)

    @property
    def material(self):
        """The material of the first primitive (None for a model file's own materials)."""
        return self.primitives[0].material if self.primitives else None

    def _counts(self, name):
        cores = (p._mesh_core() for p in self.primitives)
        return sum(getattr(core, name) for core in cores if core is not None)

    @property
    def vertex_count(self):
        return self._counts("vertex_count")

    @property
    def triangle_count(self):
        return self._counts("triangle_count")

    @property
    def point_count(self):
        """The points it draws (a point cloud's positions); 0 for a triangle mesh."""
        return self._counts("point_count")

    @staticmethod
    def from_arrays(positions, faces, normals=None, uvs=None, colors=None, texture=None, material=None):
        """A triangle mesh from arrays: positions N x 3, faces F x 3, and optional per-vertex normals, uvs and
        colours, a texture and a MetallicRoughnessMaterial.

        Any float and integer dtypes and memory orders are accepted; faces must be integers. Colours are floats in
        0..1 or uint8, N x 3 or N x 4, as displayed (sRGB-encoded), multiplying the material's base colour. A
        texture is an image H x W (x 3 or 4), top row first, uint8 or floats in 0..1, drawn with the uvs (v = 0 at
        the image's bottom row, as in OpenGL and pyrender); a material's own baseColorTexture replaces it. Without
        a material the mesh is white, a dielectric of roughness 0.5, single-sided. Bad arrays and values raise
        ValueError."""
        core = _facet.MeshCore(positions, faces, normals, uvs, colors, texture, _material_description(material))
        return Mesh([CorePrimitive(core, material)])

    @staticmethod
    def from_file(path, *, allow_external_files=False, max_triangles=DEFAULT_MAX_TRIANGLES,
                  max_points=DEFAULT_MAX_POINTS, max_texture_size=DEFAULT_MAX_TEXTURE_SIZE):
        """The whole model file as one mesh in world space (every format `facet render` reads).

        Model files are untrusted input, read within limits: the files a model names (materials, textures, buffers)
        are read only from inside its folder tree unless allow_external_files; a model placing more than
        max_triangles triangles, or more than max_points points and Gaussian splats together, is refused; a
        texture wider or taller than max_texture_size is not decoded (its material is drawn untextured, with a
        warning).

        Raises FileNotFoundError for a missing file and facet.LoadError (an OSError and a ValueError) for one that
        cannot be read, naming the file and the problem; ValueError for a limit out of range.
        """
        core = _facet.MeshCore.from_file(str(path), bool(allow_external_files), max_triangles, max_points,
                                         max_texture_size)
        return Mesh([CorePrimitive(core)])

    @staticmethod
    def from_points(points, colors=None, normals=None, is_visible=True, poses=None, material=None):
        """A point cloud: positions N x 3, each drawn as a square of the renderer's point_size pixels, with optional
        per-point colours (as Primitive's color_0) and normals, instanced by poses. With normals the points are lit
        like a surface; without, they are drawn in their colours times the material's base colour, unlit."""
        primitive = Primitive(positions=points, normals=normals, color_0=colors, mode=GLTF.POINTS, poses=poses,
                              material=material)
        return Mesh([primitive], is_visible=is_visible)

    @staticmethod
    def from_trimesh(mesh, material=None, is_visible=True, poses=None, wireframe=False, smooth=True):
        """From a trimesh.Trimesh, or a list of them (one primitive each), read by duck typing: any object with
        vertices and faces, and with vertex_normals (smooth) or face_normals (smooth=False: each face drawn flat on
        vertices of its own). Its visual's vertex or face colours (face colours need smooth=False), or its
        texture's uvs and material (PBR, or an OBJ's simple material), come along as pyrender takes them; a given
        material replaces them (copied for each primitive); without either, pyrender's grey default."""
        if isinstance(mesh, (list, tuple, set, np.ndarray)):
            meshes = list(mesh)
        elif hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
            meshes = [mesh]
        else:
            raise TypeError(f"from_trimesh: expected a trimesh.Trimesh or a list of them, got {type(mesh).__name__}")
        primitives = []
        for tm in meshes:
            vertices, faces = np.asarray(tm.vertices), np.asarray(tm.faces)
            colors, uvs, look = _trimesh_look(tm, smooth, material)
            look = copy.deepcopy(material) if material is not None else look
            if look is None:
                look = _trimesh_default_material()
            look.wireframe = bool(wireframe)
            if smooth:
                positions, normals, indices = vertices, np.asarray(tm.vertex_normals), faces
            else:
                positions, normals, indices = vertices[faces].reshape(-1, 3), np.repeat(tm.face_normals, 3, axis=0), None
            primitives.append(Primitive(positions=positions, normals=normals, texcoord_0=uvs, color_0=colors,
                                        indices=indices, material=look, mode=GLTF.TRIANGLES, poses=poses))
        return Mesh(primitives, is_visible=is_visible)


__all__ = ["DEFAULT_MAX_POINTS", "DEFAULT_MAX_TEXTURE_SIZE", "DEFAULT_MAX_TRIANGLES", "Mesh"]
