"""Colour conversion to uint8 RGBA, and ColorVisuals: per-vertex or per-face colours of a mesh."""
import numpy as np

# trimesh's grey for anything without a colour of its own (0.4 of full scale, opaque).
DEFAULT_COLOR = np.array([102, 102, 102, 255], dtype=np.uint8)


def to_rgba(colors):
    """uint8 RGBA from one colour (shape 4) or one per row (N x 4). Floats are taken as 0..1 and scaled by 255 and
    rounded, integers as 0..255; three channels get an opaque alpha. None stays None."""
    if colors is None:
        return None
    values = np.asarray(colors)
    if values.dtype == object or values.ndim not in (1, 2) or values.shape[-1] not in (3, 4):
        raise ValueError(f"colours need 3 or 4 channels, one colour or one per row; got shape {values.shape}")
    if values.dtype.kind == "f":
        values = np.round(np.clip(values, 0.0, 1.0) * 255.0)
    elif values.dtype.kind == "b":
        values = values.astype(np.int64) * 255
    elif values.dtype.kind not in "iu":
        raise ValueError(f"colours must be numbers, got dtype {values.dtype}")
    values = np.clip(values, 0, 255).astype(np.uint8)
    if values.shape[-1] == 3:
        alpha = np.full(values.shape[:-1] + (1,), 255, dtype=np.uint8)
        values = np.concatenate([values, alpha], axis=-1)
    return values


class ColorVisuals:
    """Colours of a mesh, either one per vertex (kind 'vertex') or one per face (kind 'face'); setting one kind
    clears the other. The mesh it is bound to (Trimesh.visual = ... binds it) gives the counts that a single colour
    is broadcast to."""

    def __init__(self, mesh=None, face_colors=None, vertex_colors=None):
        self.mesh = mesh
        self._kind = None
        # uint8 RGBA: one colour (4,) until a bound mesh says how many rows, else one row per vertex or face.
        self._colors = None
        if face_colors is not None:
            self.face_colors = face_colors
        if vertex_colors is not None:
            self.vertex_colors = vertex_colors

    @property
    def kind(self):
        """'vertex', 'face', or None when no colours were set."""
        return self._kind

    @property
    def defined(self):
        return self._kind is not None

    def _count(self, kind):
        if self.mesh is None:
            return None
        return len(self.mesh.vertices) if kind == "vertex" else len(self.mesh.faces)

    def _stored(self):
        """The stored colours, broadcast in place once the bound mesh gives a count, so that edits of the returned
        array stick as they do in trimesh."""
        count = self._count(self._kind)
        if self._colors.ndim == 1:
            if count is None:
                return self._colors[np.newaxis].copy()
            self._colors = np.tile(self._colors, (count, 1))
        return self._colors

    def _set(self, kind, values):
        rgba = to_rgba(values)
        if rgba is None:
            self._colors, self._kind = None, None
            return
        if rgba.ndim == 2 and rgba.shape[0] == 1:
            rgba = rgba[0]
        count = self._count(kind)
        if rgba.ndim == 2 and count is not None and rgba.shape[0] != count:
            raise ValueError(f"{rgba.shape[0]} {kind} colours for a mesh with {count} {kind}s")
        self._colors, self._kind = rgba, kind

    @property
    def vertex_colors(self):
        """uint8 N x 4: the colours set per vertex, or each vertex's mean over its faces' colours, or grey."""
        if self._kind == "vertex":
            return self._stored()
        count = self._count("vertex") or 0
        if self._kind == "face" and self.mesh is not None:
            return _face_to_vertex(self._stored(), np.asarray(self.mesh.faces), count)
        return np.tile(DEFAULT_COLOR, (count, 1))

    @vertex_colors.setter
    def vertex_colors(self, values):
        self._set("vertex", values)

    @property
    def face_colors(self):
        """uint8 F x 4: the colours set per face, or each face's mean of its vertices' colours, or grey."""
        if self._kind == "face":
            return self._stored()
        count = self._count("face") or 0
        if self._kind == "vertex" and self.mesh is not None:
            corners = self._stored()[np.asarray(self.mesh.faces)].astype(np.float64)
            return np.round(corners.mean(axis=1)).astype(np.uint8).reshape(-1, 4)
        return np.tile(DEFAULT_COLOR, (count, 1))

    @face_colors.setter
    def face_colors(self, values):
        self._set("face", values)

    def copy(self):
        """An unbound copy with its own colour array; the mesh that takes it binds it."""
        other = ColorVisuals()
        other._kind = self._kind
        other._colors = None if self._colors is None else self._colors.copy()
        return other

    def __repr__(self):
        return f"<ColorVisuals kind={self._kind!r}>"


def _face_to_vertex(face_colors, faces, vertex_count):
    """Each vertex's mean colour over the faces that use it; vertices of no face stay grey."""
    sums = np.zeros((vertex_count, 4))
    corners = faces.reshape(-1)
    for channel in range(4):
        sums[:, channel] = np.bincount(corners, weights=np.repeat(face_colors[:, channel], 3).astype(np.float64),
                                       minlength=vertex_count)
    uses = np.bincount(corners, minlength=vertex_count).astype(np.float64)
    result = np.tile(DEFAULT_COLOR, (vertex_count, 1))
    used = uses > 0
    result[used] = np.round(sums[used] / uses[used, np.newaxis]).astype(np.uint8)
    return result
