"""TextureVisuals: per-vertex uvs and a material; the materials are re-exported here, as trimesh does."""
import numpy as np

from .color import ColorVisuals
from .material import PBRMaterial, SimpleMaterial

__all__ = ["TextureVisuals", "SimpleMaterial", "PBRMaterial", "uv_to_color"]


def uv_to_color(uv, image):
    """uint8 N x 4: the nearest texel of a PIL image at each uv, with v=0 the image's bottom row (OBJ's and
    trimesh's convention). Coordinates outside 0..1 wrap around, as a repeating texture does."""
    texels = np.asarray(image.convert("RGBA"))
    height, width = texels.shape[:2]
    uv = np.asarray(uv, dtype=np.float64)
    u, v = uv[:, 0], uv[:, 1]
    u = np.where((u < 0.0) | (u > 1.0), np.mod(u, 1.0), u)
    v = np.where((v < 0.0) | (v > 1.0), np.mod(v, 1.0), v)
    column = np.clip(np.round(u * (width - 1)).astype(np.int64), 0, width - 1)
    row = np.clip(np.round((1.0 - v) * (height - 1)).astype(np.int64), 0, height - 1)
    return texels[row, column].copy()


class TextureVisuals:
    """A textured look: uv per vertex (N x 2, or None) and a SimpleMaterial or PBRMaterial. Given only an image,
    it wraps the image in a SimpleMaterial."""

    kind = "texture"

    def __init__(self, uv=None, material=None, image=None):
        self.mesh = None
        self.uv = uv
        self.material = SimpleMaterial(image=image) if material is None else material

    @property
    def uv(self):
        return self._uv

    @uv.setter
    def uv(self, values):
        if values is None:
            self._uv = None
            return
        values = np.asarray(values, dtype=np.float64)
        if values.ndim != 2 or values.shape[1] < 2:
            raise ValueError(f"uv must be N x 2, got shape {values.shape}")
        self._uv = np.ascontiguousarray(values[:, :2])

    @property
    def defined(self):
        return True

    def to_color(self):
        """A ColorVisuals with a colour per vertex: the material's image at each uv, or its main colour when it has
        no image or there are no uvs."""
        image = getattr(self.material, "image", None)
        if image is not None and self._uv is not None and len(self._uv) > 0:
            colors = uv_to_color(self._uv, image)
        else:
            colors = self.material.main_color
        visuals = ColorVisuals(mesh=self.mesh)
        visuals.vertex_colors = colors
        return visuals

    def copy(self):
        """An unbound copy with its own uv array and material copy."""
        return TextureVisuals(uv=None if self._uv is None else self._uv.copy(), material=self.material.copy())

    def __repr__(self):
        count = None if self._uv is None else len(self._uv)
        return f"<TextureVisuals uv={count} material={self.material!r}>"
