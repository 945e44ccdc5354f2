"""camera.py - pyrender's cameras: perspective, orthographic and intrinsics, with the checks pyrender makes."""
import math

import numpy as np

from ._shared import name_property
from .constants import DEFAULT_Z_FAR, DEFAULT_Z_NEAR


def _number(value, name):
    """value as a float; TypeError for None or anything that is not a number, as pyrender's float() raises."""
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name}: expected a number, got {value!r}")
    v = float(value)
    if math.isnan(v):
        raise ValueError(f"{name}: is NaN")
    return v


class Camera:
    """What every camera has: a name and the near and far clipping planes (metres along the view)."""

    def __init__(self, znear=DEFAULT_Z_NEAR, zfar=DEFAULT_Z_FAR, name=None):
        self.name = name
        self.znear = znear
        self.zfar = zfar

    name = name_property()

    @property
    def znear(self):
        return self._znear

    @znear.setter
    def znear(self, value):
        value = _number(value, "znear")
        if not 0.0 <= value < math.inf:
            raise ValueError(f"znear: must be finite and not negative, got {value}")
        self._znear = value

    @property
    def zfar(self):
        return self._zfar

    @zfar.setter
    def zfar(self, value):
        value = _number(value, "zfar")
        if not (value > 0.0 and value > self.znear and value < math.inf):
            raise ValueError(f"zfar: must be finite and beyond znear ({self.znear}), got {value}")
        self._zfar = value

    def get_projection_matrix(self, width=None, height=None):
        raise NotImplementedError

    def _projection(self, width, height, far):
        """clip_from_view for a viewport of width x height, with far as the far plane where zfar is None."""
        raise NotImplementedError


def _depth_rows(p, n, f):
    if f is None:  # the far plane at infinity, as glTF's infinite projection
        p[2, 2] = -1.0
        p[2, 3] = -2.0 * n
    else:
        p[2, 2] = (f + n) / (n - f)
        p[2, 3] = 2.0 * f * n / (n - f)
    p[3, 2] = -1.0


class PerspectiveCamera(Camera):
    """A pinhole camera: yfov, the vertical field of view in radians; aspectRatio, width over height (None: the
    viewport's); zfar None puts the far plane at infinity."""

    def __init__(self, yfov, znear=DEFAULT_Z_NEAR, zfar=None, aspectRatio=None, name=None):
        super().__init__(znear=znear, zfar=zfar, name=name)
        self.yfov = yfov
        self.aspectRatio = aspectRatio

    @property
    def yfov(self):
        return self._yfov

    @yfov.setter
    def yfov(self, value):
        value = _number(value, "yfov")
        if not 0.0 < value < math.pi:
            raise ValueError(f"yfov: must lie in (0, pi), got {value}")
        self._yfov = value

    @Camera.zfar.setter
    def zfar(self, value):
        if value is None:
            self._zfar = None
        else:
            Camera.zfar.fset(self, value)

    @property
    def aspectRatio(self):
        return self._aspectRatio

    @aspectRatio.setter
    def aspectRatio(self, value):
        if value is not None:
            value = _number(value, "aspectRatio")
            if not 0.0 < value < math.inf:
                raise ValueError(f"aspectRatio: must be positive, got {value}")
        self._aspectRatio = value

    def get_projection_matrix(self, width=None, height=None):
        """clip_from_view; width and height may be left out when aspectRatio is set."""
        return self._projection(width, height, self.zfar)

    def _projection(self, width, height, far):
        aspect = self.aspectRatio
        if aspect is None:
            if width is None or height is None:
                raise ValueError("get_projection_matrix: needs width and height when the camera has no aspectRatio")
            aspect = float(width) / float(height)
        t = math.tan(self.yfov / 2.0)
        p = np.zeros((4, 4))
        p[0, 0] = 1.0 / (aspect * t)
        p[1, 1] = 1.0 / t
        _depth_rows(p, self.znear, self.zfar if self.zfar is not None else far)
        return p


class OrthographicCamera(Camera):
    """A parallel projection showing xmag and ymag either side of the view's centre; znear must be positive."""

    def __init__(self, xmag, ymag, znear=DEFAULT_Z_NEAR, zfar=DEFAULT_Z_FAR, name=None):
        super().__init__(znear=znear, zfar=zfar, name=name)
        self.xmag = xmag
        self.ymag = ymag

    @property
    def xmag(self):
        return self._xmag

    @xmag.setter
    def xmag(self, value):
        self._xmag = _positive(value, "xmag")

    @property
    def ymag(self):
        return self._ymag

    @ymag.setter
    def ymag(self, value):
        self._ymag = _positive(value, "ymag")

    @Camera.znear.setter
    def znear(self, value):
        self._znear = _positive(value, "znear")

    def get_projection_matrix(self, width=None, height=None):
        n, f = self.znear, self.zfar
        p = np.zeros((4, 4))
        p[0, 0] = 1.0 / self.xmag
        p[1, 1] = 1.0 / self.ymag
        p[2, 2] = 2.0 / (n - f)
        p[2, 3] = (f + n) / (n - f)
        p[3, 3] = 1.0
        return p

    def _projection(self, width, height, far):
        return self.get_projection_matrix()


def _positive(value, name):
    value = _number(value, name)
    if not 0.0 < value < math.inf:
        raise ValueError(f"{name}: must be positive, got {value}")
    return value


class IntrinsicsCamera(Camera):
    """A pinhole camera given in pixels, in OpenCV's convention: a point at camera coordinates (X, Y, Z), x right,
    y down, z forward, lands at u = fx X / Z + cx, v = fy Y / Z + cy, where pixel (0, 0)'s centre is u = v = 0
    (pyrender's is half a pixel off). Its pose is camera-to-world in OpenGL axes, like every camera's."""

    def __init__(self, fx, fy, cx, cy, znear=DEFAULT_Z_NEAR, zfar=DEFAULT_Z_FAR, name=None):
        super().__init__(znear=znear, zfar=zfar, name=name)
        self.fx, self.fy, self.cx, self.cy = fx, fy, cx, cy

    def __setattr__(self, key, value):
        if key in ("fx", "fy"):
            value = _positive(value, key)
        elif key in ("cx", "cy"):
            value = _number(value, key)
            if not math.isfinite(value):
                raise ValueError(f"{key}: must be finite, got {value}")
        super().__setattr__(key, value)

    def get_projection_matrix(self, width, height):
        return self._projection(width, height, self.zfar)

    def _projection(self, width, height, far):
        p = np.zeros((4, 4))
        p[0, 0] = 2.0 * self.fx / width
        p[0, 2] = 1.0 - 2.0 * (self.cx + 0.5) / width
        p[1, 1] = 2.0 * self.fy / height
        p[1, 2] = 2.0 * (self.cy + 0.5) / height - 1.0
        _depth_rows(p, self.znear, self.zfar)
        return p


__all__ = ["Camera", "IntrinsicsCamera", "OrthographicCamera", "PerspectiveCamera"]
