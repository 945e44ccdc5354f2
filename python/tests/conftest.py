"""conftest.py - shared helpers for the facet Python tests: a UV sphere, camera poses, reading /proc."""
import numpy as np
import pytest


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


def look_at(eye, target=(0.0, 0.0, 0.0), up=(0.0, 1.0, 0.0)):
    """A camera-to-world pose in OpenGL axes (looking down -z) at eye, looking at target."""
    eye, target, up = (np.asarray(v, dtype=np.float64) for v in (eye, target, up))
    back = eye - target
    back /= np.linalg.norm(back)
    right = np.cross(up, back)
    right /= np.linalg.norm(right)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = right, np.cross(back, right), back, eye
    return pose


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


@pytest.fixture(scope="module")
def sphere():
    return uv_sphere()
