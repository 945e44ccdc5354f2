"""primitive.py - pyrender's Primitive: one draw's vertex arrays, indices, mode, material and instance poses."""
import numpy as np

from ._shared import BoxMeasures
from . import _facet
from .constants import GLTF
from .material import Material, MetallicRoughnessMaterial, _material_description

_MODE_NAMES = {GLTF.POINTS: "POINTS", GLTF.LINES: "LINES", GLTF.LINE_LOOP: "LINE_LOOP",
               GLTF.LINE_STRIP: "LINE_STRIP", GLTF.TRIANGLES: "TRIANGLES", GLTF.TRIANGLE_STRIP: "TRIANGLE_STRIP",
               GLTF.TRIANGLE_FAN: "TRIANGLE_FAN"}


def _rows(value, columns, count, name, at_least=False):
    """value as a contiguous float32 array count x columns (more columns allowed, and cut, when at_least)."""
    v = np.ascontiguousarray(np.asanyarray(value, dtype=np.float32))
    good = v.ndim == 2 and v.shape[0] == count and (v.shape[1] >= columns if at_least else v.shape[1] == columns)
    if not good:
        raise ValueError(f"{name}: expected {count} x {columns} values, one row per position, got shape {v.shape}")
    return np.ascontiguousarray(v[:, :columns])


def color_rows(value, count, name="color_0"):
    """Colours as pyrender formats them: count x 4 floats, integers read as 0..255, a single colour repeated and
    missing channels 1."""
    v = np.asanyarray(value)
    if v.dtype.kind in "iub":
        v = v / 255.0
    v = np.asarray(v, dtype=np.float32)
    if v.ndim == 1:
        v = np.tile(v, (count, 1))
    if v.ndim != 2 or v.shape[0] != count or not 1 <= v.shape[1]:
        raise ValueError(f"{name}: expected {count} colours of 3 or 4 values, got shape {v.shape}")
    if v.shape[1] < 4:
        v = np.column_stack([v, np.ones((count, 4 - v.shape[1]), dtype=np.float32)])
    return np.ascontiguousarray(v[:, :4])


def instance_poses(value):
    """Instancing poses as an array K x 4 x 4 (one 4x4 pose for K = 1), or None."""
    if value is None:
        return None
    p = np.asanyarray(value, dtype=np.float64)
    if p.ndim == 2:
        p = p[np.newaxis]
    if p.ndim != 3 or p.shape[1:] != (4, 4) or p.shape[0] == 0:
        raise ValueError(f"poses: expected one 4x4 pose or K x 4 x 4, got shape {np.shape(value)}")
    if not np.all(np.isfinite(p)):
        raise ValueError("poses: holds a non-finite value")
    return p


def posed_bounds(bounds, poses):
    """The box around bounds (2 x 3) placed by each of poses (None: as it is)."""
    if poses is None:
        return bounds
    corners = np.array([[bounds[i, 0], bounds[j, 1], bounds[k, 2], 1.0] for i in (0, 1) for j in (0, 1)
                        for k in (0, 1)])
    placed = np.einsum("kij,cj->kci", poses, corners)[..., :3].reshape(-1, 3)
    return np.array([placed.min(axis=0), placed.max(axis=0)])


def triangle_indices(mode, indices, count):
    """The triangles F x 3 that a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive draws."""
    i = np.arange(count) if indices is None else indices
    if mode == GLTF.TRIANGLES:
        if i.size % 3:
            raise ValueError(f"indices: {i.size} indices do not make whole triangles")
        return i.reshape(-1, 3)
    k = np.arange(max(i.size - 2, 0))
    if mode == GLTF.TRIANGLE_FAN:
        return np.column_stack([np.full(k.size, i[0] if i.size else 0), i[k + 1], i[k + 2]])
    # A strip's odd triangles swap their first two corners to keep the winding of the even ones.
    odd = (k % 2).astype(bool)
    return np.column_stack([np.where(odd, i[k + 1], i[k]), np.where(odd, i[k], i[k + 1]), i[k + 2]])


class Primitive(BoxMeasures):
    """Vertex arrays with one material and one mode, as pyrender's Primitive: positions N x 3; normals N x 3,
    tangents N x 4, texcoord_0 and texcoord_1 N x 2, color_0 N x 3 or 4 (floats in 0..1 or uint8); indices into
    them; mode, one of GLTF.POINTS to GLTF.TRIANGLE_FAN; poses, K x 4 x 4 instancing poses. Values are checked as
    they are set. facet draws points and triangles (lists, strips and fans); a line mode raises ValueError when it
    is drawn. tangents, texcoord_1, joints_0, weights_0 and targets are kept but not drawn."""

    def __init__(self, positions, normals=None, tangents=None, texcoord_0=None, texcoord_1=None, color_0=None,
                 joints_0=None, weights_0=None, indices=None, material=None, mode=None, targets=None, poses=None):
        self.positions = positions
        self.normals, self.tangents, self.texcoord_0, self.texcoord_1 = normals, tangents, texcoord_0, texcoord_1
        self.color_0, self.joints_0, self.weights_0, self.indices = color_0, joints_0, weights_0, indices
        self.material = material
        self.mode = GLTF.TRIANGLES if mode is None else mode
        self.targets, self.poses = targets, poses

    def __setattr__(self, key, value):
        n = len(self.positions) if key != "positions" else None
        if key == "positions":
            value = np.asanyarray(value, dtype=np.float32)
            value = np.ascontiguousarray(value.reshape(0, 3) if value.size == 0 else value)
            if value.ndim != 2 or value.shape[1] != 3:
                raise ValueError(f"positions: expected N x 3 values, got shape {value.shape}")
            if not np.all(np.isfinite(value)):
                raise ValueError("positions: holds a non-finite value")
        elif value is not None and key in ("normals", "tangents", "texcoord_0", "texcoord_1"):
            columns = {"normals": 3, "tangents": 4, "texcoord_0": 2, "texcoord_1": 2}[key]
            value = _rows(value, columns, n, key, at_least=key == "texcoord_0")
        elif value is not None and key == "color_0":
            value = color_rows(value, n)
        elif value is not None and key == "indices":
            value = np.ascontiguousarray(np.asanyarray(value)).reshape(-1)
            if value.size and (value.dtype.kind not in "iuf" or np.any(value != np.floor(value))):
                raise ValueError("indices: expected integers")
            value = value.astype(np.int64)
        elif key == "material":
            if value is None:
                value = MetallicRoughnessMaterial()
            elif not isinstance(value, Material):
                raise TypeError(f"material: expected a facet.Material, got {type(value).__name__}")
        elif key == "mode":
            value = int(value)
            if value not in _MODE_NAMES:
                raise ValueError(f"mode: expected a glTF mode 0..6, got {value}")
        elif key == "poses":
            value = instance_poses(value)
        object.__setattr__(self, key, value)
        object.__setattr__(self, "_built", None)
        object.__setattr__(self, "_box", None)

    @property
    def bounds(self):
        """2 x 3: the box around the positions, placed by every instancing pose; kept until an attribute is set
        (a frame through a camera without zfar asks for it)."""
        if self._box is None:
            box = np.zeros((2, 3))
            if len(self.positions):
                box = np.array([self.positions.min(axis=0), self.positions.max(axis=0)], dtype=np.float64)
                box = posed_bounds(box, self.poses)
            object.__setattr__(self, "_box", box)
        return self._box.copy()

    @property
    def is_transparent(self):
        """Whether it is drawn blended: its material is, or a vertex colour's alpha is below 1."""
        return self.material.is_transparent or bool(self.color_0 is not None and np.any(self.color_0[:, 3] != 1.0))

    def _mesh_core(self, flat=False):
        """The compiled mesh this primitive draws (flat: as RenderFlags.FLAT draws it), made again only after a
        change to it or its material."""
        key = (self.material, self.material._version, flat)
        built = self._built or {}
        if built.get(flat, (None,))[0] != key:
            built = {**built, flat: (key, self._make_core(flat))}
            object.__setattr__(self, "_built", built)
        return built[flat][1]

    def _make_core(self, flat):
        if len(self.positions) == 0:
            return None
        if self.mode in (GLTF.LINES, GLTF.LINE_LOOP, GLTF.LINE_STRIP):
            raise ValueError(f"Primitive: facet draws no line primitives (mode {_MODE_NAMES[self.mode]}); "
                             "RenderFlags.ALL_WIREFRAME draws triangles' edges")
        # Drawn by pyrender's conventions (python/src/materials.cpp): its lit shader's, or its flat shader's.
        description = {**_material_description(self.material), "convention": "pyrender_flat" if flat else "pyrender"}
        columns = (self.normals, self.texcoord_0, self.color_0)
        if self.mode == GLTF.POINTS:
            positions = self.positions
            if self.indices is not None:  # only the points the indices name
                _check_indices(self.indices, len(positions))
                positions = positions[self.indices]
                columns = tuple(None if c is None else c[self.indices] for c in columns)
            return _facet.MeshCore(positions, None, *columns, None, description)
        faces = triangle_indices(self.mode, self.indices, len(self.positions))
        if faces.size == 0:
            return None
        return _facet.MeshCore(self.positions, faces, *columns, None, description)


def _check_indices(indices, count):
    if indices.size and (indices.min() < 0 or indices.max() >= count):
        raise ValueError(f"indices: refer to vertices outside 0..{count - 1}")


class CorePrimitive:
    """A primitive made whole by the compiled module: a model file's meshes (Mesh.from_file) or Mesh.from_arrays'
    arrays. It has a mode, bounds and a material (None for a file's own) like Primitive, but no arrays to change."""

    mode = GLTF.TRIANGLES
    poses = None

    def __init__(self, core, material=None):
        self._core, self.material = core, material
        self._box = core.bounds  # the core never changes

    @property
    def bounds(self):
        return self._box.copy()

    @property
    def is_transparent(self):
        return self.material is not None and self.material.is_transparent

    def _mesh_core(self, flat=False):
        return self._core


__all__ = ["Primitive"]
