"""_shared.py - what pyrender's classes share: a name that is None or a str, colours, a bounding box's measures."""
import numpy as np


def name_property():
    """A `name` attribute as pyrender keeps one: None, or the value as a str."""
    def get(self):
        return self._name

    def set(self, value):
        self._name = None if value is None else str(value)

    return property(get, set, doc="None or a str.")


class BoxMeasures:
    """centroid, extents and scale of a class's `bounds` (2 x 3: the minimum and maximum corner)."""

    @property
    def centroid(self):
        return self.bounds.mean(axis=0)

    @property
    def extents(self):
        return np.diff(self.bounds, axis=0).reshape(-1)

    @property
    def scale(self):
        """The length of the box's diagonal."""
        return float(np.linalg.norm(self.extents))


def color_vector(value, length, name, fewest=1):
    """A colour as pyrender formats one, `length` values: integers are 0..255, one number stands for every channel,
    missing channels are 1 and extra ones are cut. ValueError for fewer than `fewest` values (one number aside),
    more than 4, or a value that is not finite."""
    v = np.asarray(value)
    if v.dtype.kind in "iub":
        v = v / 255.0
    v = np.asarray(v, dtype=np.float64).reshape(-1)
    if v.size == 1 and fewest <= 1:
        v = np.repeat(v, length)
    if not fewest <= v.size <= 4 or not np.all(np.isfinite(v)):
        raise ValueError(f"{name}: expected {fewest} to 4 finite values, got {value!r}")
    return np.concatenate([v, np.ones(max(0, length - v.size))])[:length]
