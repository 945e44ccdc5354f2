"""trimesh.load: pick the reader by file type and name errors after the file."""
import io
import os

from .gltf import load_gltf
from .obj import load_obj

_READERS = {"obj": load_obj, "glb": load_gltf, "gltf": load_gltf}


def load(file_obj, file_type=None, resolver=None, force=None, **kwargs):
    """A Trimesh or Scene from a path or an open binary file (which needs `file_type`): OBJ gives a Trimesh (a
    Scene for several materials), glTF/GLB a Scene. force='mesh' joins a Scene into one Trimesh, force='scene'
    wraps a Trimesh in a Scene. A missing file raises FileNotFoundError; an unknown or malformed one ValueError."""
    from ..scene import Scene
    from ..util import concatenate

    if isinstance(file_obj, (str, os.PathLike)):
        path = os.fspath(file_obj)
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{path}: no such file")
        file_type = (file_type or os.path.splitext(path)[1]).lower().lstrip(".")
        name, folder = path, os.path.dirname(os.path.abspath(path))
        with open(path, "rb") as handle:
            data = handle.read()
    else:
        name = getattr(file_obj, "name", None) or f"<{file_type} data>"
        folder = os.path.dirname(os.path.abspath(name)) if isinstance(name, str) and os.path.isfile(name) else None
        data = file_obj.read()
        file_type = (file_type or os.path.splitext(str(name))[1]).lower().lstrip(".")
    if file_type not in _READERS:
        raise ValueError(f"{name}: file type {file_type!r} is not supported (only {sorted(_READERS)})")
    result = _READERS[file_type](io.BytesIO(data), name=name, folder=folder, file_type=file_type, **kwargs)
    if force == "mesh" and isinstance(result, Scene):
        return concatenate(result.dump())
    if force == "scene" and not isinstance(result, Scene):
        return Scene(result)
    return result


def load_mesh(file_obj, file_type=None, **kwargs):
    """Like load, but always one Trimesh: a Scene's placed geometry joined in world space."""
    return load(file_obj, file_type=file_type, force="mesh", **kwargs)
