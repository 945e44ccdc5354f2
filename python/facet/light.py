"""light.py - pyrender's lights: directional, point and spot, in the physical units pyrender and glTF use."""
import math

import numpy as np

from ._shared import color_vector, name_property
from .camera import OrthographicCamera, PerspectiveCamera
from .constants import SHADOW_TEX_SZ
from .texture import Texture


def _range(value):
    if value is None:
        return None
    v = _float(value, "range")
    if not v > 0.0:
        raise ValueError(f"range: must be positive (None: unlimited), got {value!r}")
    return v


def _float(value, name):
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name}: expected a number, got {value!r}")
    return float(value)


class Light:
    """What every light has: a linear RGB colour, an intensity in pyrender's (glTF's) units and a name. The light
    is placed by its node: directional and spot lights shine along the node's -z axis."""

    kind = None

    def __init__(self, color=None, intensity=None, name=None):
        self.name = name
        self.color = np.ones(3) if color is None else color
        self.intensity = 1.0 if intensity is None else intensity
        self._shadow_texture = None

    name = name_property()

    @property
    def color(self):
        return self._color

    @color.setter
    def color(self, value):
        if value is None:
            raise ValueError("color: expected 3 or 4 finite values, got None")
        self._color = color_vector(value, 3, "color", fewest=3)

    @property
    def intensity(self):
        return self._intensity

    @intensity.setter
    def intensity(self, value):
        v = _float(value, "intensity")
        # NaN fails both comparisons; an infinite light would turn every pixel it reaches into NaN or infinity.
        if not (0.0 <= v < math.inf):
            raise ValueError(f"intensity: must be finite and not negative, got {value!r}")
        self._intensity = v

    @property
    def shadow_texture(self):
        """The shadow map pyrender's renderer would draw into (its size: facet sizes its own maps per frame)."""
        return self._shadow_texture

    @shadow_texture.setter
    def shadow_texture(self, value):
        if value is not None and not isinstance(value, Texture):
            raise TypeError("shadow_texture: expected a Texture")
        self._shadow_texture = value

    def _generate_shadow_texture(self, size=None):
        size = SHADOW_TEX_SZ if size is None else int(size)
        self.shadow_texture = Texture(width=size, height=size, source_channels="D")

    def _get_shadow_camera(self, scene_scale):
        raise NotImplementedError


class DirectionalLight(Light):
    """Light from the direction its node's +z axis points to (it shines along -z). Colour (linear RGB) times
    intensity is the irradiance, in lux, that it gives a surface facing it."""

    kind = "directional"

    def _get_shadow_camera(self, scene_scale):
        """The camera pyrender renders this light's shadow map with, for a scene of scene_scale."""
        return OrthographicCamera(xmag=scene_scale, ymag=scene_scale, znear=0.01 * scene_scale,
                                  zfar=10.0 * scene_scale)


class _RangedLight(Light):
    """A light at a point, whose light fades smoothly to none at `range` (None: unlimited)."""

    def __init__(self, color=None, intensity=None, range=None, name=None):
        super().__init__(color=color, intensity=intensity, name=name)
        self.range = range

    @property
    def range(self):
        return self._range

    @range.setter
    def range(self, value):
        self._range = _range(value)


class PointLight(_RangedLight):
    """Light from its node's position in every direction. Colour (linear RGB) times intensity is its intensity in
    candela: the irradiance at distance d is that over d^2, fading smoothly to none at `range` (None: unlimited).
    It casts no shadows, as in pyrender."""

    kind = "point"

    def _generate_shadow_texture(self, size=None):
        raise NotImplementedError("point lights cast no shadows")

    def _get_shadow_camera(self, scene_scale):
        raise NotImplementedError("point lights cast no shadows")


class SpotLight(_RangedLight):
    """A point light limited to a cone along its node's -z axis: full inside innerConeAngle, fading to none at
    outerConeAngle (half-angles in radians, 0 <= inner <= outer <= pi/2). Intensity as PointLight's, in candela."""

    kind = "spot"

    def __init__(self, color=None, intensity=None, range=None, innerConeAngle=0.0, outerConeAngle=math.pi / 4.0,
                 name=None):
        super().__init__(color=color, intensity=intensity, range=range, name=name)
        self._inner = 0.0
        self.outerConeAngle = outerConeAngle
        self.innerConeAngle = innerConeAngle

    @property
    def innerConeAngle(self):
        return self._inner

    @innerConeAngle.setter
    def innerConeAngle(self, value):
        v = _float(value, "innerConeAngle")
        if not 0.0 <= v <= self.outerConeAngle:
            raise ValueError(f"innerConeAngle: must lie in [0, outerConeAngle ({self.outerConeAngle})], got {value!r}")
        self._inner = v

    @property
    def outerConeAngle(self):
        return self._outer

    @outerConeAngle.setter
    def outerConeAngle(self, value):
        v = _float(value, "outerConeAngle")
        if not (0.0 <= v <= math.pi / 2.0 + 1e-9 and v >= self._inner):
            raise ValueError(f"outerConeAngle: must lie in [innerConeAngle, pi/2], got {value!r}")
        self._outer = min(v, math.pi / 2.0)

    def _get_shadow_camera(self, scene_scale):
        """The camera pyrender renders this light's shadow map with: the cone and a sixteenth of pi more."""
        return PerspectiveCamera(znear=0.01 * scene_scale, zfar=10.0 * scene_scale,
                                 yfov=min(2.0 * self.outerConeAngle + math.pi / 16.0, math.pi - 1e-9),
                                 aspectRatio=1.0)


def light_tuple(light, pose, shadows=False):
    """The light at pose as the compiled renderer takes it: (kind, vector, colour, intensity, spot direction, range,
    inner cone, outer cone, casts shadows), the vector being the direction towards a directional light or the
    light's position."""
    if light.kind == "directional":
        vector = pose[:3, 2]
    else:
        vector = pose[:3, 3]
    # A spot shines along its node's -z axis, as in pyrender and glTF.
    direction = -pose[:3, 2]
    # pyrender draws a cone whose angles are equal with a hard edge; the renderer needs inner below outer for that.
    outer = max(getattr(light, "outerConeAngle", math.pi / 4.0), 1e-6)
    inner = min(getattr(light, "innerConeAngle", 0.0), outer * (1.0 - 1e-6))
    return (light.kind, vector, light.color, light.intensity, direction, getattr(light, "range", None), inner, outer,
            bool(shadows))


__all__ = ["DirectionalLight", "Light", "PointLight", "SpotLight"]
