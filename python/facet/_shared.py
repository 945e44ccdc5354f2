"""_shared.py - what pyrender's classes share: a name that is None or a str, and the measures of a bounding box."""
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
