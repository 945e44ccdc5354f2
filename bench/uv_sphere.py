"""uv_sphere.py - the Python benchmarks' UV sphere as numpy arrays: unit normals (its positions too) and triangles."""
import numpy as np


def uv_sphere(rings, segments):
    """(positions, normals, faces) of a unit UV sphere of 2 x rings x segments triangles, counter-clockwise seen
    from outside."""
    theta = np.linspace(0.0, np.pi, rings + 1)
    phi = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    normals = np.stack([np.sin(t) * np.cos(p), np.cos(t), -np.sin(t) * np.sin(p)], axis=-1).reshape(-1, 3)
    a = (np.arange(rings)[:, None] * (segments + 1) + np.arange(segments)[None, :]).reshape(-1)
    b = a + segments + 1
    faces = np.concatenate([np.stack([a, b, a + 1], 1), np.stack([a + 1, b, b + 1], 1)])
    return normals, normals, faces
