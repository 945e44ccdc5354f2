"""node.py - pyrender's Node: a mesh, camera or light with a local transform and children, in a scene's tree."""
import numpy as np

from ._shared import name_property


def matrix_from_trs(translation, rotation, scale):
    """T R S as a 4x4 matrix; rotation is a unit quaternion (x, y, z, w), as glTF stores it."""
    x, y, z, w = rotation
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3] = r * np.asarray(scale, dtype=np.float64)[np.newaxis, :]
    m[:3, 3] = translation
    return m


def trs_from_matrix(m):
    """(translation, rotation (x, y, z, w), scale) of an affine matrix without shear; a reflection shows as a
    negative x scale, as pyrender decomposes it."""
    basis = m[:3, :3]
    scale = np.linalg.norm(basis, axis=0)
    if np.linalg.det(basis) < 0.0:
        scale[0] = -scale[0]
    r = basis / np.where(scale == 0.0, 1.0, scale)[np.newaxis, :]
    # Shepperd's method: start from the largest of w, x, y, z so that the square root is well away from zero.
    trace = np.trace(r)
    candidates = [trace, r[0, 0], r[1, 1], r[2, 2]]
    k = int(np.argmax(candidates))
    if k == 0:
        s = 2.0 * np.sqrt(max(1.0 + trace, 0.0))
        q = [(r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s, 0.25 * s]
    elif k == 1:
        s = 2.0 * np.sqrt(max(1.0 + r[0, 0] - r[1, 1] - r[2, 2], 0.0))
        q = [0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s, (r[2, 1] - r[1, 2]) / s]
    elif k == 2:
        s = 2.0 * np.sqrt(max(1.0 - r[0, 0] + r[1, 1] - r[2, 2], 0.0))
        q = [(r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s, (r[0, 2] - r[2, 0]) / s]
    else:
        s = 2.0 * np.sqrt(max(1.0 - r[0, 0] - r[1, 1] + r[2, 2], 0.0))
        q = [(r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s, (r[1, 0] - r[0, 1]) / s]
    q = np.array(q)
    if q[3] < 0.0:
        q = -q
    return m[:3, 3].copy(), q / np.linalg.norm(q), scale


def _vector(value, size, name):
    v = np.asanyarray(value, dtype=np.float64)
    if v.shape != (size,):
        raise ValueError(f"{name}: expected a ({size},) vector, got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name}: holds a non-finite value")
    return v


class Node:
    """A place in a scene's tree: at most one mesh, camera and light, a transform relative to its parent (a 4x4
    matrix, or translation, rotation as a unit quaternion (x, y, z, w) and scale, kept consistent), and children.

    `id` is the node's number in the id buffer: set by the scene that first holds it, unless given."""

    def __init__(self, name=None, camera=None, children=None, skin=None, matrix=None, mesh=None, rotation=None,
                 scale=None, translation=None, weights=None, light=None, id=None):
        self._matrix = None
        if matrix is None:
            self.translation = np.zeros(3) if translation is None else translation
            self.rotation = np.array([0.0, 0.0, 0.0, 1.0]) if rotation is None else rotation
            self.scale = np.ones(3) if scale is None else scale
        else:
            self.matrix = matrix
        self.name, self.camera, self.mesh, self.light = name, camera, mesh, light
        self.children = [] if children is None else children
        self.skin, self.weights, self.id = skin, weights, id

    name = name_property()

    @property
    def mesh(self):
        return self._mesh

    @mesh.setter
    def mesh(self, value):
        from .mesh import Mesh
        if value is not None and not isinstance(value, Mesh):
            raise TypeError(f"mesh: expected a facet.Mesh, got {type(value).__name__}")
        self._mesh = value

    @property
    def camera(self):
        return self._camera

    @camera.setter
    def camera(self, value):
        from .camera import Camera
        if value is not None and not isinstance(value, Camera):
            raise TypeError(f"camera: expected a facet camera, got {type(value).__name__}")
        self._camera = value

    @property
    def light(self):
        return self._light

    @light.setter
    def light(self, value):
        from .light import Light
        if value is not None and not isinstance(value, Light):
            raise TypeError(f"light: expected a facet light, got {type(value).__name__}")
        self._light = value

    @property
    def translation(self):
        return self._translation

    @translation.setter
    def translation(self, value):
        self._translation = _vector(value, 3, "translation")
        self._matrix = None

    @property
    def rotation(self):
        """The unit quaternion (x, y, z, w) of the rotation."""
        return self._rotation

    @rotation.setter
    def rotation(self, value):
        q = _vector(value, 4, "rotation")
        if abs(np.linalg.norm(q) - 1.0) > 1e-3:
            raise ValueError(f"rotation: a quaternion must have norm 1, got {np.linalg.norm(q):g}")
        self._rotation = q
        self._matrix = None

    @property
    def scale(self):
        return self._scale

    @scale.setter
    def scale(self, value):
        self._scale = _vector(value, 3, "scale")
        self._matrix = None

    @property
    def matrix(self):
        """The 4x4 transform from this node's space to its parent's: a copy (set the whole matrix, not an element)."""
        if self._matrix is None:
            self._matrix = matrix_from_trs(self._translation, self._rotation, self._scale)
        return self._matrix.copy()

    @matrix.setter
    def matrix(self, value):
        m = np.array(value, dtype=np.float64)
        if m.shape != (4, 4):
            raise ValueError(f"matrix: expected a 4x4 matrix, got shape {m.shape}")
        if not np.all(np.isfinite(m)):
            raise ValueError("matrix: holds a non-finite value")
        if not np.allclose(m[3], [0.0, 0.0, 0.0, 1.0]):
            raise ValueError("matrix: the bottom row must be [0, 0, 0, 1]")
        translation, rotation, scale = trs_from_matrix(m)
        self.translation, self.rotation, self.scale = translation, rotation, scale
        self._matrix = m


__all__ = ["Node"]
