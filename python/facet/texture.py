"""texture.py - pyrender's Texture and Sampler: an image for a material, and how it is filtered and wrapped."""
import numpy as np

from ._shared import name_property
from .constants import GLTF

_FILTERS = (None, GLTF.NEAREST, GLTF.LINEAR, GLTF.NEAREST_MIPMAP_NEAREST, GLTF.LINEAR_MIPMAP_NEAREST,
            GLTF.NEAREST_MIPMAP_LINEAR, GLTF.LINEAR_MIPMAP_LINEAR)
_WRAPS = (GLTF.CLAMP_TO_EDGE, GLTF.MIRRORED_REPEAT, GLTF.REPEAT)


class Sampler:
    """glTF's sampler. facet filters every texture with mipmaps and trilinear filtering and repeats it, whatever
    the sampler says; the values are checked and kept."""

    def __init__(self, name=None, magFilter=None, minFilter=None, wrapS=GLTF.REPEAT, wrapT=GLTF.REPEAT):
        self.name = name
        for key, value, allowed in (("magFilter", magFilter, _FILTERS), ("minFilter", minFilter, _FILTERS),
                                    ("wrapS", wrapS, _WRAPS), ("wrapT", wrapT, _WRAPS)):
            if value not in allowed:
                raise ValueError(f"{key}: {value!r} is not a glTF value for it")
            setattr(self, key, value)

    name = name_property()


def image_array(source, name="texture"):
    """An image (numpy array, PIL image, or anything numpy reads as one) as an array H x W or H x W x C, uint8 or
    floats; ValueError for anything else."""
    image = np.asarray(source)
    if image.dtype.kind not in "fiub" or image.ndim not in (2, 3) or (image.ndim == 3 and image.shape[2] > 4):
        raise ValueError(f"{name}: expected an image H x W (x 1 to 4), got {type(source).__name__} of shape "
                         f"{image.shape}")
    if image.dtype.kind == "b":
        image = image.astype(np.uint8) * 255
    if image.dtype.kind in "iu" and image.dtype != np.uint8:
        # pyrender casts integer images to bytes; out-of-range values would wrap around there, so refuse them here.
        if image.size and (image.min() < 0 or image.max() > 255):
            raise ValueError(f"{name}: integer values must lie in 0..255")
        image = image.astype(np.uint8)
    return image


class Texture:
    """An image and its sampler, as pyrender's Texture: source is an array H x W (x C), top row first, uint8 or
    floats in 0..1, or a PIL image. width and height are those of the source (or given, for a texture without
    one, such as a light's shadow map)."""

    def __init__(self, name=None, sampler=None, source=None, source_channels=None, width=None, height=None,
                 tex_type=None, data_format=None):
        self.name = name
        self.sampler = Sampler() if sampler is None else sampler
        self.source_channels = source_channels
        self.tex_type, self.data_format = tex_type, data_format
        self.source = source
        if source is None:
            self.width, self.height = width, height

    name = name_property()

    @property
    def source(self):
        return self._source

    @source.setter
    def source(self, value):
        self._source = None if value is None else image_array(value)
        if self._source is not None:
            self.height, self.width = self._source.shape[:2]

    def is_transparent(self, cutoff=1.0):
        """Whether any texel's alpha is below cutoff (0..1)."""
        s = self._source
        if s is None or s.ndim != 3 or s.shape[2] not in (2, 4):
            return False
        alpha = s[..., -1] / 255.0 if s.dtype == np.uint8 else s[..., -1]
        return bool(np.any(alpha < cutoff))


__all__ = ["Sampler", "Texture"]
