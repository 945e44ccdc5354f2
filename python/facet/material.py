"""material.py - pyrender's MetallicRoughnessMaterial: glTF's physically based surface description for a Mesh."""
import numbers

import numpy as np

from .texture import Texture, image_array

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
    """A texture as an image array H x W (x C) for the compiled module, which checks its size and values.
    data_channels: two channels are green and blue (a metallic-roughness image), given a zero red channel."""
    if texture is None or texture.source is None:
        return None
    image = texture.source
    if data_channels and image.ndim == 3 and image.shape[2] == 2:
        image = np.concatenate([np.zeros_like(image[..., :1]), image], axis=2)
    return image


_TEXTURES = ("normalTexture", "occlusionTexture", "emissiveTexture", "baseColorTexture", "metallicRoughnessTexture")


class Material:
    """What every material has, as pyrender's Material: a name, textures for normals, occlusion and emission, the
    emissive factor, the alpha mode and cutoff, and the sidedness. Values are checked as they are set; a texture
    may be given as an image (numpy array or PIL image) and is kept as a facet.Texture."""

    def __setattr__(self, key, value):
        if key in _TEXTURES:
            if value is not None and not isinstance(value, Texture):
                value = Texture(source=image_array(value, key))
        elif key in ("doubleSided", "smooth", "wireframe"):
            value = _flag(value, key)
        elif key == "alphaMode":
            value = "OPAQUE" if value is None else value
            if value not in ALPHA_MODES:
                raise ValueError(f"alphaMode: expected one of {', '.join(ALPHA_MODES)}, got {value!r}")
        elif key == "alphaCutoff":
            value = _unit(value, 0.5, key)
        elif key in ("metallicFactor", "roughnessFactor"):
            value = _unit(value, 1.0, key)
        elif key == "emissiveFactor":
            value = _factor_vector(np.zeros(3) if value is None else value, 3, key, np.inf)
        elif key == "baseColorFactor":
            value = _factor_vector(np.ones(4) if value is None else value, 4, key, 1.0)
        elif key == "name":
            value = None if value is None else str(value)
        object.__setattr__(self, key, value)
        # Meshes compare it with the one they last drew with, to see that the material changed.
        object.__setattr__(self, "_version", getattr(self, "_version", 0) + 1)

    @property
    def is_transparent(self):
        """Whether it is drawn blended: pyrender's rule (alpha below 1 in BLEND mode, below the cutoff in MASK)."""
        if self.alphaMode == "OPAQUE":
            return False
        cutoff = 1.0 if self.alphaMode == "BLEND" else self.alphaCutoff
        base = getattr(self, "baseColorFactor", np.ones(4))
        texture = getattr(self, "baseColorTexture", None)
        return bool(base[3] < cutoff or (texture is not None and texture.is_transparent(cutoff)))

    @property
    def textures(self):
        """The set of the Textures it holds."""
        return {t for t in (getattr(self, k, None) for k in _TEXTURES) if t is not None}


class MetallicRoughnessMaterial(Material):
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

    Changes to a material show in the next frame of every mesh that has it.
    """

    def __init__(self, name=None, normalTexture=None, occlusionTexture=None, emissiveTexture=None,
                 emissiveFactor=None, alphaMode=None, alphaCutoff=None, doubleSided=False, smooth=True,
                 wireframe=False, baseColorFactor=None, baseColorTexture=None, metallicFactor=1.0,
                 roughnessFactor=1.0, metallicRoughnessTexture=None):
        self.name = name
        self.normalTexture, self.occlusionTexture = normalTexture, occlusionTexture
        self.emissiveTexture, self.emissiveFactor = emissiveTexture, emissiveFactor
        self.alphaMode, self.alphaCutoff = alphaMode, alphaCutoff
        self.doubleSided, self.smooth, self.wireframe = doubleSided, smooth, wireframe
        self.baseColorFactor, self.baseColorTexture = baseColorFactor, baseColorTexture
        self.metallicFactor, self.roughnessFactor = metallicFactor, roughnessFactor
        self.metallicRoughnessTexture = metallicRoughnessTexture

    def _core_dict(self):
        """The material as the compiled module takes it (python/src/materials.hpp); every value was checked when set."""
        return {
            "name": "" if self.name is None else self.name,
            "base_color": self.baseColorFactor,
            "metallic": self.metallicFactor,
            "roughness": self.roughnessFactor,
            "emissive": self.emissiveFactor,
            "alpha_mode": self.alphaMode,
            "alpha_cutoff": self.alphaCutoff,
            "double_sided": self.doubleSided,
            "base_color_texture": _image(self.baseColorTexture, "baseColorTexture"),
            "metallic_roughness_texture": _image(self.metallicRoughnessTexture, "metallicRoughnessTexture", True),
            "emissive_texture": _image(self.emissiveTexture, "emissiveTexture"),
            "occlusion_texture": _image(self.occlusionTexture, "occlusionTexture"),
            "normal_texture": _image(self.normalTexture, "normalTexture"),
        }


def _material_description(material):
    """A mesh's material as the compiled module takes it; warns where facet draws it differently from pyrender."""
    if material is None:
        return None
    if not isinstance(material, MetallicRoughnessMaterial):
        raise ValueError(f"material: expected a facet.MetallicRoughnessMaterial, got {type(material).__name__}")
    return material._core_dict()


__all__ = ["Material", "MetallicRoughnessMaterial"]
