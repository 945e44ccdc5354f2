"""Primitive meshes: box, cylinder, icosphere, uv sphere and a coloured axis marker, faces counter-clockwise outward."""
import itertools

import numpy as np

from . import transformations, util
from .base import Trimesh
from .visual import ColorVisuals

# Corner i of the unit box has x, y, z from bits 0, 1, 2 of i; two triangles per side, wound outward.
_BOX_FACES = np.array([[0, 6, 2], [0, 4, 6], [1, 3, 7], [1, 7, 5], [0, 1, 5], [0, 5, 4],
                       [2, 7, 3], [2, 6, 7], [0, 3, 1], [0, 2, 3], [4, 5, 7], [4, 7, 6]], dtype=np.int64)


def _finish(vertices, faces, transform):
    mesh = Trimesh(vertices=vertices, faces=faces)
    if transform is not None:
        mesh.apply_transform(transform)
    return mesh


def box(extents=None, transform=None, bounds=None, **kwargs):
    """An axis-aligned box of 8 vertices and 12 triangles centred on the origin (size `extents`, default 1), or
    spanning `bounds` [[min], [max]], then moved by `transform`."""
    corners = np.array([[(i >> axis) & 1 for axis in range(3)] for i in range(8)], dtype=np.float64)
    if bounds is not None:
        bounds = np.asarray(bounds, dtype=np.float64)
        vertices = bounds[0] + corners * (bounds[1] - bounds[0])
    else:
        extents = np.ones(3) if extents is None else np.asarray(extents, dtype=np.float64).reshape(3)
        vertices = (corners - 0.5) * extents
    return _finish(vertices, _BOX_FACES.copy(), transform)


def _z_to_segment(segment):
    """The transform that takes the z axis from -h/2..h/2 onto the segment between two points, and its length."""
    start, end = np.asarray(segment, dtype=np.float64)
    direction = end - start
    length = float(np.linalg.norm(direction))
    direction = direction / length
    axis = np.cross([0.0, 0.0, 1.0], direction)
    if np.linalg.norm(axis) < 1e-12:
        matrix = np.eye(4) if direction[2] > 0 else transformations.rotation_matrix(np.pi, [1.0, 0.0, 0.0])
    else:
        matrix = transformations.rotation_matrix(np.arccos(np.clip(direction[2], -1.0, 1.0)), axis)
    matrix[:3, 3] = (start + end) / 2.0
    return matrix, length


def cylinder(radius=1.0, height=1.0, sections=32, segment=None, transform=None, **kwargs):
    """A capped cylinder along z, centred on the origin: 2 + 2 * sections vertices (cap centres, then the bottom
    and top rings) and 4 * sections triangles. With `segment` (two points) it spans them instead."""
    if segment is not None:
        placement, height = _z_to_segment(segment)
        transform = placement if transform is None else np.asarray(transform) @ placement
    sections = int(sections)
    if sections < 3:
        raise ValueError(f"a cylinder needs at least 3 sections, got {sections}")
    angles = np.linspace(0.0, 2.0 * np.pi, sections, endpoint=False)
    ring = np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])
    half = height / 2.0
    vertices = np.vstack([[0.0, 0.0, -half], [0.0, 0.0, half],
                          np.column_stack([ring, np.full(sections, -half)]),
                          np.column_stack([ring, np.full(sections, half)])])
    k = np.arange(sections)
    after = (k + 1) % sections
    bottom, top = 2 + k, 2 + sections + k
    bottom_next, top_next = 2 + after, 2 + sections + after
    faces = np.vstack([
        np.column_stack([np.zeros(sections, dtype=np.int64), bottom_next, bottom]),
        np.column_stack([np.ones(sections, dtype=np.int64), top, top_next]),
        np.column_stack([bottom, bottom_next, top_next]),
        np.column_stack([bottom, top_next, top]),
    ])
    return _finish(vertices, faces, transform)


def _icosahedron():
    """The 12 unit vertices and 20 outward faces of a regular icosahedron."""
    golden = (1.0 + np.sqrt(5.0)) / 2.0
    vertices = []
    for a, b in itertools.product((-1.0, 1.0), repeat=2):
        vertices += [[0.0, a, b * golden], [a, b * golden, 0.0], [b * golden, 0.0, a]]
    vertices = np.array(vertices)
    # The faces are the triples of mutually adjacent vertices (edge length 2); wind each so it faces outward.
    faces = []
    for triple in itertools.combinations(range(12), 3):
        points = vertices[list(triple)]
        if np.allclose(np.linalg.norm(points - np.roll(points, 1, axis=0), axis=1), 2.0):
            normal = np.cross(points[1] - points[0], points[2] - points[0])
            faces.append(triple if normal @ points.sum(axis=0) > 0 else triple[::-1])
    return util.unitize(vertices), np.array(faces, dtype=np.int64)


def icosphere(subdivisions=3, radius=1.0, **kwargs):
    """A sphere from an icosahedron whose faces are split in four `subdivisions` times, with every new vertex
    pushed onto the sphere: 10 * 4**n + 2 vertices and 20 * 4**n faces."""
    vertices, faces = _icosahedron()
    for _ in range(int(subdivisions)):
        edges = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        middles = util.unitize(vertices[unique[:, 0]] + vertices[unique[:, 1]])
        mid = inverse.reshape(-1, 3) + len(vertices)
        ab, bc, ca = mid[:, 0], mid[:, 1], mid[:, 2]
        a, b, c = faces[:, 0], faces[:, 1], faces[:, 2]
        faces = np.vstack([np.column_stack(t) for t in ((a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca))])
        vertices = np.vstack([vertices, middles])
    return Trimesh(vertices=vertices * radius, faces=faces)


def uv_sphere(radius=1.0, count=(32, 32), **kwargs):
    """A latitude-longitude sphere with poles on z: count[0] latitude bands, count[1] longitude segments, one
    vertex at each pole and 2 + (count[0] - 1) * count[1] vertices in all."""
    bands, segments = int(count[0]), int(count[1])
    if bands < 2 or segments < 3:
        raise ValueError(f"a uv sphere needs count of at least (2, 3), got {tuple(count)}")
    theta = np.pi * np.arange(1, bands) / bands
    phi = 2.0 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    rings = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1).reshape(-1, 3)
    vertices = np.vstack([[0.0, 0.0, 1.0], rings, [0.0, 0.0, -1.0]]) * radius
    south = len(vertices) - 1
    k = np.arange(segments)
    after = (k + 1) % segments
    faces = [np.column_stack([np.zeros(segments, dtype=np.int64), 1 + k, 1 + after])]
    for band in range(bands - 2):
        upper, lower = 1 + band * segments, 1 + (band + 1) * segments
        faces.append(np.column_stack([upper + k, lower + k, lower + after]))
        faces.append(np.column_stack([upper + k, lower + after, upper + after]))
    last = 1 + (bands - 2) * segments
    faces.append(np.column_stack([np.full(segments, south), last + after, last + k]))
    return Trimesh(vertices=vertices, faces=np.vstack(faces))


def axis(origin_size=0.04, transform=None, origin_color=None, axis_radius=None, axis_length=None, **kwargs):
    """A marker for a frame: a ball at the origin and red, green and blue rods along +x, +y and +z, coloured per
    vertex."""
    axis_radius = origin_size / 5.0 if axis_radius is None else axis_radius
    axis_length = origin_size * 10.0 if axis_length is None else axis_length
    ball = icosphere(subdivisions=2, radius=origin_size)
    ball.visual = ColorVisuals(vertex_colors=[255, 255, 255, 255] if origin_color is None else origin_color)
    parts = [ball]
    # Rod i turns from +z onto its axis: about y for x, about -x for y, not at all for z.
    turns = [transformations.rotation_matrix(np.pi / 2.0, [0.0, 1.0, 0.0]),
             transformations.rotation_matrix(-np.pi / 2.0, [1.0, 0.0, 0.0]), np.eye(4)]
    for index, turn in enumerate(turns):
        rod = cylinder(radius=axis_radius, height=axis_length, sections=16,
                       transform=turn @ transformations.translation_matrix([0.0, 0.0, axis_length / 2.0]))
        color = np.zeros(4, dtype=np.uint8)
        color[index], color[3] = 255, 255
        rod.visual = ColorVisuals(vertex_colors=color)
        parts.append(rod)
    marker = util.concatenate(parts)
    if transform is not None:
        marker.apply_transform(transform)
    return marker
