"""Materials: SimpleMaterial (an OBJ/MTL-style diffuse colour and image) and PBRMaterial (glTF metallic-roughness)."""
import copy

import numpy as np

from .color import DEFAULT_COLOR, to_rgba

_ALPHA_MODES = (None, "OPAQUE", "MASK", "BLEND")


def _rgba_or_default(value):
    return DEFAULT_COLOR.copy() if value is None else to_rgba(value)


class SimpleMaterial:
    """A diffuse colour with an optional PIL image, plus ambient, specular and glossiness. Keys of an MTL file
    that have no attribute of their own (Ns, Ka, illum, ...) are kept in `kwargs`, as trimesh keeps them."""

    def __init__(self, image=None, diffuse=None, ambient=None, specular=None, glossiness=None, name=None,
                 **kwargs):
        self.image = image
        self.diffuse = _rgba_or_default(diffuse)
        self.ambient = _rgba_or_default(ambient)
        self.specular = _rgba_or_default(specular)
        self.glossiness = 1.0 if glossiness is None else float(glossiness)
        self.name = name
        self.kwargs = kwargs

    @property
    def main_color(self):
        """uint8 RGBA: the colour a mesh shows without its image."""
        return self.diffuse

    def copy(self):
        """A copy with its own colours and kwargs; the image is shared, as nothing here draws into it."""
        other = copy.copy(self)
        other.diffuse, other.ambient, other.specular = (c.copy() for c in (self.diffuse, self.ambient, self.specular))
        other.kwargs = copy.deepcopy(self.kwargs)
        return other

    def __repr__(self):
        return f"<SimpleMaterial name={self.name!r} diffuse={self.diffuse.tolist()} image={self.image is not None}>"


class PBRMaterial:
    """A glTF 2.0 metallic-roughness material. Factors left None mean "the glTF default" to whoever renders it;
    baseColorFactor is uint8 RGBA, emissiveFactor float RGB, the textures are PIL images."""

    def __init__(self, name=None, emissiveFactor=None, emissiveTexture=None, baseColorFactor=None,
                 metallicFactor=None, roughnessFactor=None, normalTexture=None, occlusionTexture=None,
                 baseColorTexture=None, metallicRoughnessTexture=None, doubleSided=False, alphaMode=None,
                 alphaCutoff=None, **kwargs):
        if alphaMode not in _ALPHA_MODES:
            raise ValueError(f"alphaMode must be one of {_ALPHA_MODES}, got {alphaMode!r}")
        self.name = name
        self.baseColorFactor = to_rgba(baseColorFactor)
        self.emissiveFactor = None if emissiveFactor is None else np.asarray(emissiveFactor, dtype=np.float64)
        self.metallicFactor = None if metallicFactor is None else float(metallicFactor)
        self.roughnessFactor = None if roughnessFactor is None else float(roughnessFactor)
        self.baseColorTexture = baseColorTexture
        self.metallicRoughnessTexture = metallicRoughnessTexture
        self.normalTexture = normalTexture
        self.occlusionTexture = occlusionTexture
        self.emissiveTexture = emissiveTexture
        self.doubleSided = bool(doubleSided)
        self.alphaMode = alphaMode
        self.alphaCutoff = None if alphaCutoff is None else float(alphaCutoff)
        self.kwargs = kwargs

    @property
    def image(self):
        """The base colour texture, under the name SimpleMaterial uses."""
        return self.baseColorTexture

    @property
    def main_color(self):
        """uint8 RGBA: the base colour factor, white when the file gave none (glTF's default)."""
        if self.baseColorFactor is None:
            return np.full(4, 255, dtype=np.uint8)
        return self.baseColorFactor

    def copy(self):
        """A copy with its own factor arrays; the images are shared, as nothing here draws into them."""
        other = copy.copy(self)
        for attribute in ("baseColorFactor", "emissiveFactor"):
            value = getattr(self, attribute)
            setattr(other, attribute, None if value is None else value.copy())
        other.kwargs = copy.deepcopy(self.kwargs)
        return other

    def __repr__(self):
        return f"<PBRMaterial name={self.name!r} baseColorFactor={self.baseColorFactor}>"
