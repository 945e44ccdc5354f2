"""Small helpers trimesh users reach for: unit vectors and joining meshes into one."""
import numpy as np


def unitize(vectors):
    """Rows (or one vector) scaled to length 1; zero-length ones stay zero rather than becoming NaN."""
    vectors = np.asarray(vectors, dtype=np.float64)
    lengths = np.linalg.norm(vectors, axis=-1, keepdims=True)
    safe = np.where(lengths > 1e-300, lengths, 1.0)
    return np.where(lengths > 1e-300, vectors / safe, 0.0)


def is_sequence(value):
    """True for lists, tuples, sets and arrays that are not scalars; strings are not sequences here."""
    if isinstance(value, (str, bytes, dict)):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim > 0
    return isinstance(value, (list, tuple, set))


def concatenate(a, b=None):
    """One Trimesh holding every face of the given meshes (a list, or two meshes). Colours survive when every
    mesh has ColorVisuals and one of them set colours; a shared material survives when every mesh has uvs for it."""
    from .base import Trimesh
    from .visual import ColorVisuals, TextureVisuals

    meshes = list(a) if is_sequence(a) else [a]
    if b is not None:
        meshes.extend(b if is_sequence(b) else [b])
    if not meshes:
        return Trimesh()
    offsets = np.cumsum([0] + [len(m.vertices) for m in meshes[:-1]])
    vertices = np.vstack([m.vertices for m in meshes])
    faces = np.vstack([m.faces + offset for m, offset in zip(meshes, offsets)])
    normals = np.vstack([m.vertex_normals for m in meshes])
    visual = None
    visuals = [m.visual for m in meshes]
    if all(isinstance(v, ColorVisuals) for v in visuals) and any(v.defined for v in visuals):
        if all(v.kind == "face" for v in visuals):
            visual = ColorVisuals(face_colors=np.vstack([v.face_colors for v in visuals]))
        else:
            visual = ColorVisuals(vertex_colors=np.vstack([v.vertex_colors for v in visuals]))
    elif (all(isinstance(v, TextureVisuals) and v.uv is not None for v in visuals)
          and all(v.material is visuals[0].material for v in visuals)):
        visual = TextureVisuals(uv=np.vstack([v.uv for v in visuals]), material=visuals[0].material)
    return Trimesh(vertices=vertices, faces=faces, vertex_normals=normals, visual=visual)
