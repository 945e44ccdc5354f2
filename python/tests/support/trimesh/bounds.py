"""Axis-aligned bounding boxes: their eight corners."""
import numpy as np


def corners(bounds):
    """8 x 3: every corner of the box [[min x, min y, min z], [max x, max y, max z]], x changing fastest."""
    bounds = np.asarray(bounds, dtype=np.float64)
    if bounds.shape != (2, 3):
        raise ValueError(f"bounds must be 2 x 3, got shape {bounds.shape}")
    index = np.arange(8)
    pick = np.stack([index & 1, (index >> 1) & 1, (index >> 2) & 1], axis=1)
    return bounds[pick, np.arange(3)]
