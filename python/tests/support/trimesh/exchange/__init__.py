"""Readers for mesh files: OBJ (with MTL) and glTF 2.0 (GLB or JSON)."""
from . import gltf, load, obj

__all__ = ["gltf", "load", "obj"]
