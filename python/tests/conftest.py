"""conftest.py - shared helpers for the facet Python tests: a UV sphere, camera poses, reading /proc."""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from poses import look_at  # noqa: E402,F401  (the tests import it from here)


def uv_sphere(radius=1.0, rings=128, segments=256, center=(0.0, 0.0, 0.0)):
    """Positions, faces and normals of a UV sphere, counter-clockwise seen from outside."""
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    normals = np.stack([np.sin(t) * np.cos(p), np.cos(t), -np.sin(t) * np.sin(p)], axis=-1).reshape(-1, 3)
    positions = normals * radius + np.asarray(center)
    faces = []
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            faces.append((a, b, a + 1))
            faces.append((a + 1, b, b + 1))
    faces = np.array(faces, dtype=np.int64)
    area = np.linalg.norm(np.cross(positions[faces[:, 1]] - positions[faces[:, 0]],
                                   positions[faces[:, 2]] - positions[faces[:, 0]]), axis=1)
    return positions, faces[area > 1e-12], normals


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


@pytest.fixture(scope="module")
def sphere():
    return uv_sphere()
