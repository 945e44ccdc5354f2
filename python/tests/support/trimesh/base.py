"""Trimesh: a triangle mesh with vertices, faces, normals, bounds and a visual (colours or a texture)."""
import numpy as np

from . import util
from .visual import ColorVisuals


class Trimesh:
    """Vertices (float64 N x 3) and triangles (int64 F x 3, counter-clockwise seen from outside). Vertex normals
    given to it are kept (made unit length); otherwise they are the area-weighted mean of the adjacent face normals,
    computed from the current vertices whenever asked. `process` is accepted for trimesh's signature; nothing is
    merged or removed, so the arrays stay as given."""

    def __init__(self, vertices=None, faces=None, face_normals=None, vertex_normals=None, face_colors=None,
                 vertex_colors=None, metadata=None, process=False, visual=None, **kwargs):
        self._vertex_normals = None
        self._face_normals = None
        self._vertices = np.zeros((0, 3))
        self._faces = np.zeros((0, 3), dtype=np.int64)
        self.vertices = np.zeros((0, 3)) if vertices is None else vertices
        self.faces = np.zeros((0, 3), dtype=np.int64) if faces is None else faces
        if face_normals is not None:
            self.face_normals = face_normals
        if vertex_normals is not None:
            self.vertex_normals = vertex_normals
        self.metadata = dict(metadata or {})
        self.visual = ColorVisuals(face_colors=face_colors, vertex_colors=vertex_colors) if visual is None else visual

    @property
    def vertices(self):
        return self._vertices

    @vertices.setter
    def vertices(self, values):
        values = np.array(values, dtype=np.float64)
        if values.size == 0:
            values = values.reshape(0, 3)
        if values.ndim != 2 or values.shape[1] != 3:
            raise ValueError(f"vertices must be N x 3, got shape {values.shape}")
        # New positions make given normals stale, as trimesh drops its cached normals when vertices change.
        self._vertex_normals = None
        self._face_normals = None
        self._vertices = values

    @property
    def faces(self):
        return self._faces

    @faces.setter
    def faces(self, values):
        values = np.array(values)
        if values.size == 0:
            values = values.reshape(0, 3)
        if values.ndim != 2 or values.shape[1] != 3 or values.dtype.kind not in "iu":
            raise ValueError(f"faces must be F x 3 integers, got shape {values.shape} of {values.dtype}")
        values = values.astype(np.int64)
        if values.size and (values.min() < 0 or values.max() >= len(self._vertices)):
            raise ValueError(f"faces index vertices 0..{len(self._vertices) - 1}, got {values.min()}..{values.max()}")
        self._faces = values
        self._face_normals = None

    @property
    def visual(self):
        return self._visual

    @visual.setter
    def visual(self, value):
        # Binding lets the visual broadcast one colour to this mesh's vertex or face count.
        value.mesh = self
        self._visual = value

    @property
    def triangles(self):
        """F x 3 x 3: the corners of each face."""
        return self._vertices[self._faces]

    def _face_cross(self):
        corners = self.triangles
        return np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])

    @property
    def face_normals(self):
        """F x 3 unit normals by the right-hand rule; zero for degenerate faces."""
        if self._face_normals is not None and len(self._face_normals) == len(self._faces):
            return self._face_normals
        return util.unitize(self._face_cross())

    @face_normals.setter
    def face_normals(self, values):
        values = np.asarray(values, dtype=np.float64)
        if values.shape != self._faces.shape:
            raise ValueError(f"face_normals must be {self._faces.shape}, got {values.shape}")
        self._face_normals = util.unitize(values)

    @property
    def vertex_normals(self):
        """N x 3 unit normals: those given, or each vertex's area-weighted mean of its faces' normals."""
        if self._vertex_normals is not None:
            return self._vertex_normals
        # The cross product's length is twice the face area, so summing it weights each face by its area.
        cross = self._face_cross()
        count = len(self._vertices)
        corners = self._faces.reshape(-1)
        summed = np.zeros((count, 3))
        for axis in range(3):
            summed[:, axis] = np.bincount(corners, weights=np.repeat(cross[:, axis], 3), minlength=count)
        return util.unitize(summed)

    @vertex_normals.setter
    def vertex_normals(self, values):
        if values is None:
            self._vertex_normals = None
            return
        values = np.asarray(values, dtype=np.float64)
        if values.shape != self._vertices.shape:
            raise ValueError(f"vertex_normals must be {self._vertices.shape}, got {values.shape}")
        # OBJ files (fuze.obj among them) carry normals that are not unit length; renderers expect unit ones.
        self._vertex_normals = util.unitize(values)

    @property
    def area_faces(self):
        return np.linalg.norm(self._face_cross(), axis=1) / 2.0

    @property
    def area(self):
        return float(self.area_faces.sum())

    @property
    def is_empty(self):
        return len(self._vertices) == 0

    @property
    def bounds(self):
        """2 x 3 [min, max] corners of the vertices, or None for an empty mesh."""
        if self.is_empty:
            return None
        return np.array([self._vertices.min(axis=0), self._vertices.max(axis=0)])

    @property
    def extents(self):
        bounds = self.bounds
        return None if bounds is None else bounds[1] - bounds[0]

    @property
    def scale(self):
        """The length of the bounding box's diagonal."""
        extents = self.extents
        return 0.0 if extents is None else float(np.linalg.norm(extents))

    @property
    def centroid(self):
        """The area-weighted mean of the face centres (the surface's centre), or the vertices' mean without area."""
        if self.is_empty:
            return None
        areas = self.area_faces
        if areas.sum() <= 0.0:
            return self._vertices.mean(axis=0)
        return (self.triangles.mean(axis=1) * areas[:, np.newaxis]).sum(axis=0) / areas.sum()

    def copy(self, **kwargs):
        """An independent copy: its own arrays and a copy of the visual."""
        return Trimesh(vertices=self._vertices.copy(), faces=self._faces.copy(),
                       vertex_normals=None if self._vertex_normals is None else self._vertex_normals.copy(),
                       face_normals=None if self._face_normals is None else self._face_normals.copy(),
                       metadata=dict(self.metadata), visual=self._visual.copy())

    def apply_transform(self, matrix):
        """Transform in place by a 4 x 4 matrix and return self. Given normals turn with the inverse transpose;
        a mirroring matrix also reverses the winding so faces keep facing outward."""
        matrix = np.asarray(matrix, dtype=np.float64)
        if matrix.shape != (4, 4):
            raise ValueError(f"transform must be 4 x 4, got shape {matrix.shape}")
        linear = matrix[:3, :3]
        moved = self._vertices @ linear.T + matrix[:3, 3]
        if matrix[3, :3].any() or matrix[3, 3] != 1.0:
            homogeneous = self._vertices @ matrix[3, :3] + matrix[3, 3]
            moved = moved / homogeneous[:, np.newaxis]
        normal_matrix = np.linalg.inv(linear).T if abs(np.linalg.det(linear)) > 1e-300 else linear
        vertex_normals, face_normals = self._vertex_normals, self._face_normals
        self._vertices = moved
        if np.linalg.det(linear) < 0.0:
            self._faces = np.ascontiguousarray(self._faces[:, ::-1])
        self._vertex_normals = None if vertex_normals is None else util.unitize(vertex_normals @ normal_matrix.T)
        self._face_normals = None if face_normals is None else util.unitize(face_normals @ normal_matrix.T)
        return self

    def apply_translation(self, translation):
        matrix = np.eye(4)
        matrix[:3, 3] = translation
        return self.apply_transform(matrix)

    def apply_scale(self, scaling):
        matrix = np.eye(4)
        matrix[:3, :3] *= scaling
        return self.apply_transform(matrix)

    def __repr__(self):
        return f"<trimesh.Trimesh(vertices.shape={self._vertices.shape}, faces.shape={self._faces.shape})>"
