"""material.py - pyrender's MetallicRoughnessMaterial: glTF's physically based surface description for a Mesh."""
import numbers

import numpy as np

ALPHA_MODES = ("OPAQUE", "MASK", "BLEND")


def _factor_vector(value, length, name, upper):
    """A colour factor as pyrender reads one: a number stands for every channel, integer values are 0..255, and
    missing channels are 1. Returns float64 values of `length`, each finite and in [0, upper]."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        value = value / 255.0
    if isinstance(value, numbers.Real):
        value = np.full(length, float(value))
    v = np.asarray(value).squeeze()
    if v.dtype.kind in "iu":
        v = v / 255.0
    if v.dtype.kind not in "fiu" or v.ndim != 1 or not 1 <= v.size <= 4:
        raise ValueError(f"{name}: expected up to 4 numbers, got {value!r}")
    v = np.asarray(v, dtype=np.float64)
    v = np.concatenate([v, np.ones(max(0, length - v.size))])[:length]
    if not (np.all(np.isfinite(v)) and np.all(v >= 0.0) and np.all(v <= upper)):
        raise ValueError(f"{name}: values must lie in 0..{upper:g}, got {value!r}")
    return v


def _unit(value, default, name):
    if value is None:
        return default
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected a number in [0, 1], got {value!r}") from None
    if not 0.0 <= v <= 1.0:
        raise ValueError(f"{name}: must lie in [0, 1], got {value!r}")
    return v


def _flag(value, name):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected True or False, got {value!r}")
    return bool(value)


def _image(texture, name, data_channels=False):
    """A texture as an image array H x W (x C) for the compiled module, which checks its size and values: numpy
    arrays and anything numpy reads as one (PIL images), or an object holding one as `source` (pyrender.Texture).
    data_channels: two channels are green and blue (a metallic-roughness image), given a zero red channel."""
    if texture is None:
        return None
    image = np.asarray(getattr(texture, "source", texture))
    if image.dtype.kind not in "fiu" or image.ndim not in (2, 3):
        raise ValueError(f"{name}: expected an image H x W, H x W x 3 or H x W x 4, got {type(texture).__name__} "
                         f"of shape {image.shape}")
    if image.dtype.kind in "iu" and image.dtype != np.uint8:
        # pyrender casts integer images to bytes; out-of-range values would wrap around there, so refuse them here.
        if image.size and (image.min() < 0 or image.max() > 255):
            raise ValueError(f"{name}: integer values must lie in 0..255")
        image = image.astype(np.uint8)
    if data_channels and image.ndim == 3 and image.shape[2] == 2:
        image = np.concatenate([np.zeros_like(image[..., :1]), image], axis=2)
    return image


class MetallicRoughnessMaterial:
    """glTF's metallic-roughness material, as pyrender spells it; give it to Mesh(..., material=) or
    Mesh.from_trimesh(tm, material=).

    baseColorFactor: linear RGBA (alpha 1 if 3 values; integers are 0..255, as in pyrender), multiplying the
    baseColorTexture and the vertex colours. metallicFactor and roughnessFactor: 0..1, multiplying the blue and
    green channels of metallicRoughnessTexture. emissiveFactor: linear RGB radiance, unbounded, multiplying the
    emissiveTexture. alphaMode: "OPAQUE" (alpha ignored), "MASK" (drawn where alpha >= alphaCutoff) or "BLEND".
    doubleSided: back faces are drawn (lit from their own side) instead of culled. Textures are images H x W (x 3
    or 4), top row first, uint8 or floats in 0..1, or pyrender.Texture objects; they need a mesh with uvs.
    occlusionTexture reads red; normalTexture is tangent space. smooth is kept but changes nothing, as in pyrender;
    wireframe is not drawn per material (RenderFlags.ALL_WIREFRAME draws every mesh as lines).

    A mesh reads its material when it is made: change a material before making meshes with it.
    """

    def __init__(self, name=None, normalTexture=None, occlusionTexture=None, emissiveTexture=None,
                 emissiveFactor=None, alphaMode=None, alphaCutoff=None, doubleSided=False, smooth=True,
                 wireframe=False, baseColorFactor=None, baseColorTexture=None, metallicFactor=1.0,
                 roughnessFactor=1.0, metallicRoughnessTexture=None):
        self.name = name
        self.normalTexture, self.occlusionTexture = normalTexture, occlusionTexture
        self.emissiveTexture = emissiveTexture
        self.emissiveFactor = np.zeros(3) if emissiveFactor is None else emissiveFactor
        self.alphaMode = "OPAQUE" if alphaMode is None else alphaMode
        self.alphaCutoff = 0.5 if alphaCutoff is None else alphaCutoff
        self.doubleSided, self.smooth, self.wireframe = doubleSided, smooth, wireframe
        self.baseColorFactor = np.ones(4) if baseColorFactor is None else baseColorFactor
        self.baseColorTexture, self.metallicRoughnessTexture = baseColorTexture, metallicRoughnessTexture
        self.metallicFactor, self.roughnessFactor = metallicFactor, roughnessFactor
        self._core_dict()  # bad values raise here, where they are given

    def _core_dict(self):
        """The material as the compiled module takes it (python/src/materials.hpp), every value checked."""
        if self.alphaMode not in ALPHA_MODES:
            raise ValueError(f"alphaMode: expected one of {', '.join(ALPHA_MODES)}, got {self.alphaMode!r}")
        _flag(self.smooth, "smooth")
        _flag(self.wireframe, "wireframe")
        return {
            "name": "" if self.name is None else str(self.name),
            "base_color": _factor_vector(self.baseColorFactor, 4, "baseColorFactor", 1.0),
            "metallic": _unit(self.metallicFactor, 1.0, "metallicFactor"),
            "roughness": _unit(self.roughnessFactor, 1.0, "roughnessFactor"),
            "emissive": _factor_vector(self.emissiveFactor, 3, "emissiveFactor", np.inf),
            "alpha_mode": self.alphaMode,
            "alpha_cutoff": _unit(self.alphaCutoff, 0.5, "alphaCutoff"),
            "double_sided": _flag(self.doubleSided, "doubleSided"),
            "base_color_texture": _image(self.baseColorTexture, "baseColorTexture"),
            "metallic_roughness_texture": _image(self.metallicRoughnessTexture, "metallicRoughnessTexture", True),
            "emissive_texture": _image(self.emissiveTexture, "emissiveTexture"),
            "occlusion_texture": _image(self.occlusionTexture, "occlusionTexture"),
            "normal_texture": _image(self.normalTexture, "normalTexture"),
        }


__all__ = ["MetallicRoughnessMaterial"]
