"""light.py - pyrender's lights: directional, point and spot, in the physical units pyrender and glTF use."""
import math

import numpy as np


def _color(value, default, name):
    """An RGB(A) colour as a float array of 4, alpha 1 if not given; uint8 values are scaled by 1/255."""
    if value is None:
        value = default
    c = np.asarray(value)
    if c.dtype == np.uint8:
        c = c / 255.0
    c = np.asarray(c, dtype=np.float64).reshape(-1)
    if c.size not in (3, 4) or not np.all(np.isfinite(c)):
        raise ValueError(f"{name}: expected 3 or 4 finite values, got {value!r}")
    return np.append(c, 1.0) if c.size == 3 else c


def _intensity(value):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"intensity: expected a number, got {value!r}") from None
    # NaN fails both comparisons; an infinite light would turn every pixel it reaches into NaN or infinity.
    if not (0.0 <= v < math.inf):
        raise ValueError(f"intensity: must be finite and not negative, got {value!r}")
    return v


def _range(value):
    if value is None:
        return None
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"range: expected a positive number or None, got {value!r}") from None
    if not v > 0.0:
        raise ValueError(f"range: must be positive (None: unlimited), got {value!r}")
    return v


class DirectionalLight:
    """Light from the direction its node's +z axis points to (it shines along -z). Colour (linear RGB) times
    intensity is the irradiance, in lux, that it gives a surface facing it."""

    kind = "directional"

    def __init__(self, color=None, intensity=1.0, name=None):
        self.color, self.intensity, self.name = _color(color, (1.0, 1.0, 1.0), "color")[:3], _intensity(intensity), name


class PointLight:
    """Light from its node's position in every direction. Colour (linear RGB) times intensity is its intensity in
    candela: the irradiance at distance d is that over d^2, fading smoothly to none at `range` (None: unlimited)."""

    kind = "point"

    def __init__(self, color=None, intensity=1.0, range=None, name=None):
        self.color, self.intensity, self.name = _color(color, (1.0, 1.0, 1.0), "color")[:3], _intensity(intensity), name
        self.range = _range(range)


class SpotLight:
    """A point light limited to a cone along its node's -z axis: full inside innerConeAngle, fading to none at
    outerConeAngle (half-angles in radians, 0 <= inner < outer <= pi/2). Intensity as PointLight's, in candela."""

    kind = "spot"

    def __init__(self, color=None, intensity=1.0, range=None, innerConeAngle=0.0, outerConeAngle=math.pi / 4.0,
                 name=None):
        self.color, self.intensity, self.name = _color(color, (1.0, 1.0, 1.0), "color")[:3], _intensity(intensity), name
        self.range = _range(range)
        try:
            inner, outer = float(innerConeAngle), float(outerConeAngle)
        except (TypeError, ValueError):
            raise ValueError(f"innerConeAngle, outerConeAngle: expected numbers, got {innerConeAngle!r}, "
                             f"{outerConeAngle!r}") from None
        if not 0.0 < outer <= math.pi / 2.0:
            raise ValueError(f"outerConeAngle: must lie in (0, pi/2], got {outerConeAngle!r}")
        if not 0.0 <= inner < outer:
            raise ValueError(f"innerConeAngle: must lie in [0, outerConeAngle), got {innerConeAngle!r} with "
                             f"outerConeAngle {outerConeAngle!r}")
        self.innerConeAngle, self.outerConeAngle = inner, outer


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
    inner = getattr(light, "innerConeAngle", 0.0)
    outer = getattr(light, "outerConeAngle", math.pi / 4.0)
    return (light.kind, vector, light.color, light.intensity, direction, getattr(light, "range", None), inner, outer,
            bool(shadows))


__all__ = ["DirectionalLight", "PointLight", "SpotLight"]
