"""4 x 4 homogeneous transforms and (w, x, y, z) quaternions, with the names and conventions trimesh exposes."""
import math

import numpy as np


def identity_matrix():
    return np.eye(4)


def unit_vector(data, axis=None):
    """`data` scaled to length 1 (along `axis` for arrays of vectors)."""
    data = np.array(data, dtype=np.float64)
    if axis is None:
        return data / np.linalg.norm(data)
    return data / np.linalg.norm(data, axis=axis, keepdims=True)


def translation_matrix(direction):
    matrix = np.eye(4)
    matrix[:3, 3] = np.asarray(direction, dtype=np.float64)[:3]
    return matrix


def translation_from_matrix(matrix):
    return np.array(matrix, dtype=np.float64)[:3, 3].copy()


def scale_matrix(factor, origin=None):
    """Uniform scaling by `factor` about `origin` (the coordinate origin by default)."""
    matrix = np.diag([factor, factor, factor, 1.0])
    if origin is not None:
        matrix[:3, 3] = (1.0 - factor) * np.asarray(origin, dtype=np.float64)[:3]
    return matrix


def rotation_matrix(angle, direction, point=None):
    """Right-handed rotation by `angle` radians about the axis `direction` through `point` (the origin if None)."""
    axis = unit_vector(np.asarray(direction, dtype=np.float64)[:3])
    sine, cosine = math.sin(angle), math.cos(angle)
    # Rodrigues: R = cos I + sin [axis]x + (1 - cos) axis axis^T.
    cross = np.array([[0.0, -axis[2], axis[1]],
                      [axis[2], 0.0, -axis[0]],
                      [-axis[1], axis[0], 0.0]])
    matrix = np.eye(4)
    matrix[:3, :3] = cosine * np.eye(3) + sine * cross + (1.0 - cosine) * np.outer(axis, axis)
    if point is not None:
        point = np.asarray(point, dtype=np.float64)[:3]
        matrix[:3, 3] = point - matrix[:3, :3] @ point
    return matrix


def quaternion_about_axis(angle, axis):
    """(w, x, y, z) of the rotation by `angle` radians about `axis`."""
    axis = unit_vector(np.asarray(axis, dtype=np.float64)[:3])
    return np.concatenate([[math.cos(angle / 2.0)], math.sin(angle / 2.0) * axis])


def quaternion_matrix(quaternion):
    """4 x 4 rotation of a (w, x, y, z) quaternion, which need not be unit length; a zero one is the identity."""
    q = np.array(quaternion, dtype=np.float64)
    norm_sq = q @ q
    if norm_sq < 1e-300:
        return np.eye(4)
    w, x, y, z = q * math.sqrt(2.0 / norm_sq)
    matrix = np.eye(4)
    matrix[:3, :3] = [[1.0 - y * y - z * z, x * y - z * w, x * z + y * w],
                      [x * y + z * w, 1.0 - x * x - z * z, y * z - x * w],
                      [x * z - y * w, y * z + x * w, 1.0 - x * x - y * y]]
    return matrix


def quaternion_from_matrix(matrix, isprecise=False):
    """Unit (w, x, y, z) of the rotation in a 3 x 3 or 4 x 4 matrix, with w >= 0. `isprecise` is accepted for
    trimesh's signature; the largest-pivot method used here is accurate for any rotation matrix."""
    m = np.asarray(matrix, dtype=np.float64)[:3, :3]
    trace = np.trace(m)
    # Divide by whichever of 4w^2, 4x^2, 4y^2, 4z^2 is largest, so no division is by a number near zero.
    if trace > max(m[0, 0], m[1, 1], m[2, 2]):
        s = math.sqrt(trace + 1.0) * 2.0
        q = [s / 4.0, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif m[0, 0] >= m[1, 1] and m[0, 0] >= m[2, 2]:
        s = math.sqrt(max(1.0 + m[0, 0] - m[1, 1] - m[2, 2], 0.0)) * 2.0
        q = [(m[2, 1] - m[1, 2]) / s, s / 4.0, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif m[1, 1] >= m[2, 2]:
        s = math.sqrt(max(1.0 + m[1, 1] - m[0, 0] - m[2, 2], 0.0)) * 2.0
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, s / 4.0, (m[1, 2] + m[2, 1]) / s]
    else:
        s = math.sqrt(max(1.0 + m[2, 2] - m[0, 0] - m[1, 1], 0.0)) * 2.0
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, s / 4.0]
    q = unit_vector(q)
    return -q if q[0] < 0.0 else q


def quaternion_multiply(quaternion1, quaternion0):
    """The (w, x, y, z) product q1 * q0: rotate by q0, then by q1."""
    w1, x1, y1, z1 = np.asarray(quaternion1, dtype=np.float64)
    w0, x0, y0, z0 = np.asarray(quaternion0, dtype=np.float64)
    return np.array([w1 * w0 - x1 * x0 - y1 * y0 - z1 * z0,
                     w1 * x0 + x1 * w0 + y1 * z0 - z1 * y0,
                     w1 * y0 - x1 * z0 + y1 * w0 + z1 * x0,
                     w1 * z0 + x1 * y0 - y1 * x0 + z1 * w0])


def quaternion_conjugate(quaternion):
    q = np.array(quaternion, dtype=np.float64)
    q[1:] = -q[1:]
    return q


def euler_matrix(ai, aj, ak, axes="sxyz"):
    """4 x 4 rotation from three angles. axes is 's' (static frame) or 'r' (rotating frame) and three axis letters:
    'sxyz' turns by ai about x, then aj about fixed y, then ak about fixed z; 'rxyz' turns about x, then the new
    y, then the newest z."""
    if not isinstance(axes, str) or len(axes) != 4 or axes[0] not in "sr" or any(a not in "xyz" for a in axes[1:]):
        raise ValueError(f"axes must be like 'sxyz' or 'rzyx', got {axes!r}")
    unit = {"x": [1.0, 0.0, 0.0], "y": [0.0, 1.0, 0.0], "z": [0.0, 0.0, 1.0]}
    turns = [rotation_matrix(angle, unit[letter]) for angle, letter in zip((ai, aj, ak), axes[1:])]
    if axes[0] == "s":
        return turns[2] @ turns[1] @ turns[0]
    return turns[0] @ turns[1] @ turns[2]


def inverse_matrix(matrix):
    return np.linalg.inv(np.asarray(matrix, dtype=np.float64))


def concatenate_matrices(*matrices):
    """The product of the matrices in order, so the last is applied first."""
    result = np.eye(4)
    for matrix in matrices:
        result = result @ np.asarray(matrix, dtype=np.float64)
    return result


def transform_points(points, matrix):
    """N x 3 points moved by a 4 x 4 matrix."""
    points = np.asarray(points, dtype=np.float64)
    matrix = np.asarray(matrix, dtype=np.float64)
    return points @ matrix[:3, :3].T + matrix[:3, 3]
