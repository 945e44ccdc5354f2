"""Tests of the trimesh stand-in (tests/support): primitives, Trimesh, transforms, colours and materials."""
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

# The stand-in lives beside the tests rather than on the global path; facet itself never imports trimesh.
sys.path.insert(0, str(Path(__file__).resolve().parent / "support"))
import trimesh  # noqa: E402
from trimesh import transformations as tf  # noqa: E402


def faces_point_outward(mesh):
    """Every face normal points away from the origin (true for convex shapes centred there)."""
    centres = mesh.triangles.mean(axis=1)
    return bool(np.all(np.einsum("ij,ij->i", mesh.face_normals, centres) > 0))


def edges_are_manifold(mesh):
    """Each directed edge appears once and its reverse once: closed and consistently wound."""
    directed = mesh.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    forward = {tuple(e) for e in directed}
    return len(forward) == len(directed) and all((b, a) in forward for a, b in forward)


# --- primitives -------------------------------------------------------------------------------------------------

def test_box_is_unit_centred_closed_and_outward():
    box = trimesh.creation.box()
    assert box.vertices.dtype == np.float64 and box.faces.dtype == np.int64
    assert box.vertices.shape == (8, 3) and box.faces.shape == (12, 3)
    assert np.allclose(box.bounds, [[-0.5] * 3, [0.5] * 3])
    assert np.isclose(box.area, 6.0)
    assert faces_point_outward(box) and edges_are_manifold(box)
    # Each face normal is a coordinate axis, every one of the six used twice.
    axes, counts = np.unique(np.round(box.face_normals).astype(int), axis=0, return_counts=True)
    assert len(axes) == 6 and np.all(counts == 2)


def test_box_extents_and_transform():
    box = trimesh.creation.box(extents=[1.0, 2.0, 4.0], transform=tf.translation_matrix([1.0, 0.0, -1.0]))
    assert np.allclose(box.bounds, [[0.5, -1.0, -3.0], [1.5, 1.0, 1.0]])
    assert np.allclose(box.extents, [1.0, 2.0, 4.0])
    assert np.allclose(box.centroid, [1.0, 0.0, -1.0])


def test_cylinder_counts_bounds_area_and_normals():
    sections = 24
    cyl = trimesh.creation.cylinder(radius=0.1, height=2.0, sections=sections)
    assert cyl.vertices.shape == (2 + 2 * sections, 3) and cyl.faces.shape == (4 * sections, 3)
    assert np.allclose(cyl.bounds, [[-0.1, -0.1, -1.0], [0.1, 0.1, 1.0]])
    chord = 2 * 0.1 * np.sin(np.pi / sections)
    cap = sections / 2 * 0.1 ** 2 * np.sin(2 * np.pi / sections)
    assert np.isclose(cyl.area, sections * chord * 2.0 + 2 * cap)
    assert faces_point_outward(cyl) and edges_are_manifold(cyl)


def test_cylinder_along_segment():
    cyl = trimesh.creation.cylinder(radius=0.5, segment=[[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], sections=8)
    assert np.isclose(cyl.bounds[0, 0], 0.0) and np.isclose(cyl.bounds[1, 0], 2.0)


@pytest.mark.parametrize("subdivisions", [0, 1, 3])
def test_icosphere_counts_radius_and_normals(subdivisions):
    sphere = trimesh.creation.icosphere(subdivisions=subdivisions, radius=0.05)
    assert sphere.vertices.shape == (10 * 4 ** subdivisions + 2, 3)
    assert sphere.faces.shape == (20 * 4 ** subdivisions, 3)
    assert np.allclose(np.linalg.norm(sphere.vertices, axis=1), 0.05)
    assert faces_point_outward(sphere) and edges_are_manifold(sphere)
    # Smooth normals of a sphere point along the position.
    assert np.all(np.einsum("ij,ij->i", sphere.vertex_normals, sphere.vertices / 0.05) > 0.98)


def test_uv_sphere_counts_radius_and_normals():
    sphere = trimesh.creation.uv_sphere(radius=2.0, count=(8, 12))
    assert sphere.vertices.shape == (2 + 7 * 12, 3) and sphere.faces.shape == (2 * 12 + 2 * 12 * 6, 3)
    assert np.allclose(np.linalg.norm(sphere.vertices, axis=1), 2.0)
    assert faces_point_outward(sphere) and edges_are_manifold(sphere)


def test_axis_marker_is_coloured_per_vertex():
    marker = trimesh.creation.axis(origin_size=0.1)
    assert marker.visual.kind == "vertex"
    colors = marker.visual.vertex_colors
    for index in range(3):
        # The rod's tip along each axis is coloured by that axis's channel.
        tip = np.argmax(marker.vertices[:, index])
        expected = np.zeros(4, np.uint8)
        expected[index] = expected[3] = 255
        assert np.array_equal(colors[tip], expected)


# --- Trimesh ----------------------------------------------------------------------------------------------------

def test_vertex_normals_are_area_weighted_and_given_ones_unitized():
    # Two triangles share vertex 0: a big one facing +z and a small one facing +x.
    vertices = [[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0.1, 0], [0, 0, 0.1]]
    mesh = trimesh.Trimesh(vertices=vertices, faces=[[0, 1, 2], [0, 3, 4]])
    expected = np.array([0.01 / 2, 0.0, 4.0 / 2])
    assert np.allclose(mesh.vertex_normals[0], expected / np.linalg.norm(expected))
    assert np.allclose(mesh.face_normals, [[0, 0, 1], [1, 0, 0]])
    given = trimesh.Trimesh(vertices=vertices, faces=[[0, 1, 2], [0, 3, 4]],
                            vertex_normals=np.tile([0, 0, 3.0], (5, 1)))
    assert np.allclose(given.vertex_normals, [0, 0, 1])


def test_bad_faces_raise():
    with pytest.raises(ValueError):
        trimesh.Trimesh(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces=[[0, 1, 3]])


def test_apply_transform_moves_vertices_and_normals():
    mesh = trimesh.creation.box()
    mesh.vertex_normals = mesh.vertex_normals
    turn = tf.rotation_matrix(np.pi / 2, [0, 0, 1])
    matrix = tf.translation_matrix([1, 2, 3]) @ turn
    before_v, before_n = mesh.vertices.copy(), mesh.vertex_normals.copy()
    assert mesh.apply_transform(matrix) is mesh
    assert np.allclose(mesh.vertices, before_v @ turn[:3, :3].T + [1, 2, 3])
    assert np.allclose(mesh.vertex_normals, before_n @ turn[:3, :3].T)


def test_mirroring_transform_keeps_faces_outward():
    mesh = trimesh.creation.box().apply_transform(np.diag([-1.0, 1.0, 1.0, 1.0]))
    assert faces_point_outward(mesh)


def test_copy_is_independent():
    mesh = trimesh.creation.box()
    mesh.visual.vertex_colors = [255, 0, 0]
    other = mesh.copy()
    other.vertices[0] = [9, 9, 9]
    other.visual.vertex_colors = [0, 255, 0]
    assert not np.allclose(mesh.vertices[0], [9, 9, 9])
    assert np.array_equal(mesh.visual.vertex_colors[0], [255, 0, 0, 255])
    assert other.visual.mesh is other


def test_bounds_corners():
    corners = trimesh.bounds.corners([[0, 0, 0], [1, 2, 3]])
    assert corners.shape == (8, 3)
    assert {tuple(c) for c in corners} == {(x, y, z) for x in (0, 1) for y in (0, 2) for z in (0, 3)}


# --- transformations --------------------------------------------------------------------------------------------

def test_rotation_matrix_agrees_with_quaternions():
    rng = np.random.default_rng(7)
    for _ in range(20):
        angle, axis = rng.uniform(-np.pi, np.pi), rng.normal(size=3)
        matrix = tf.rotation_matrix(angle, axis)
        q = tf.quaternion_about_axis(angle, axis)
        assert np.isclose(np.linalg.norm(q), 1.0)
        assert np.allclose(tf.quaternion_matrix(q), matrix)
        back = tf.quaternion_from_matrix(matrix)
        assert np.allclose(back, q) or np.allclose(back, -q)
        assert back[0] >= 0
        assert np.allclose(matrix[:3, :3] @ matrix[:3, :3].T, np.eye(3))


def test_rotation_matrix_conventions():
    quarter = tf.rotation_matrix(np.pi / 2, [0, 0, 1])
    assert np.allclose(quarter @ [1, 0, 0, 1], [0, 1, 0, 1])
    assert np.allclose(tf.quaternion_about_axis(np.pi / 2, [0, 0, 1]), [np.sqrt(0.5), 0, 0, np.sqrt(0.5)])
    about_point = tf.rotation_matrix(np.pi / 3, [1, 1, 0], point=[1, 2, 3])
    assert np.allclose(about_point @ [1, 2, 3, 1], [1, 2, 3, 1])
    assert np.allclose(tf.translation_matrix([1, 2, 3])[:3, 3], [1, 2, 3])
    assert np.array_equal(tf.identity_matrix(), np.eye(4))


def test_euler_matrix_sxyz_turns_about_x_then_y_then_z():
    ai, aj, ak = 0.3, -0.7, 1.1
    expected = (tf.rotation_matrix(ak, [0, 0, 1]) @ tf.rotation_matrix(aj, [0, 1, 0])
                @ tf.rotation_matrix(ai, [1, 0, 0]))
    assert np.allclose(tf.euler_matrix(ai, aj, ak), expected)
    assert np.allclose(tf.euler_matrix(ai, aj, ak, "rzyx"), tf.euler_matrix(ak, aj, ai, "sxyz"))


# --- colours ----------------------------------------------------------------------------------------------------

def test_new_mesh_has_empty_bound_color_visuals():
    box = trimesh.creation.box()
    assert isinstance(box.visual, trimesh.visual.ColorVisuals)
    assert box.visual.kind is None and not box.visual.defined
    assert box.visual.mesh is box
    assert box.visual.vertex_colors.shape == (8, 4)


def test_single_colour_broadcasts_and_floats_become_uint8():
    box = trimesh.creation.box()
    box.visual.vertex_colors = [0.2, 0.5, 1.0]
    colors = box.visual.vertex_colors
    assert colors.dtype == np.uint8 and colors.shape == (8, 4)
    assert np.all(colors == [51, 128, 255, 255])
    box.visual.face_colors = np.array([10, 20, 30, 40])
    assert box.visual.face_colors.shape == (12, 4) and np.all(box.visual.face_colors == [10, 20, 30, 40])


def test_per_row_colours_and_wrong_counts():
    box = trimesh.creation.box()
    rows = np.random.default_rng(1).uniform(size=(8, 3))
    box.visual.vertex_colors = rows
    assert np.array_equal(box.visual.vertex_colors[:, :3], np.round(rows * 255).astype(np.uint8))
    assert np.all(box.visual.vertex_colors[:, 3] == 255)
    with pytest.raises(ValueError):
        box.visual.vertex_colors = np.zeros((5, 4))
    with pytest.raises(ValueError):
        box.visual.face_colors = np.zeros((12, 2))


def test_setting_one_kind_clears_the_other():
    box = trimesh.creation.box()
    box.visual.vertex_colors = [255, 0, 0, 255]
    assert box.visual.kind == "vertex" and box.visual.defined
    box.visual.face_colors = [0.0, 0.0, 1.0, 1.0]
    assert box.visual.kind == "face"
    # Vertex colours are now the mean over each vertex's faces: all blue.
    assert np.all(box.visual.vertex_colors == [0, 0, 255, 255])
    box.visual.vertex_colors = [0, 255, 0]
    assert box.visual.kind == "vertex"
    assert np.all(box.visual.face_colors == [0, 255, 0, 255])


def test_texture_visuals_to_color_samples_nearest_texel_bottom_up():
    # Rows top to bottom: red, green over blue, white.
    image = Image.fromarray(np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [255, 255, 255]]], np.uint8))
    visual = trimesh.visual.TextureVisuals(uv=[[0, 0], [1, 0], [0, 1], [1, 1], [0.9, 0.1]], image=image)
    assert visual.kind == "texture" and visual.defined
    colors = visual.to_color().vertex_colors
    assert np.array_equal(colors[:, :3], [[0, 0, 255], [255, 255, 255], [255, 0, 0], [0, 255, 0], [255, 255, 255]])
    plain = trimesh.visual.TextureVisuals(material=trimesh.visual.texture.SimpleMaterial(diffuse=[1.0, 0, 0]))
    mesh = trimesh.creation.box()
    mesh.visual = plain
    mesh.visual = mesh.visual.to_color()
    assert mesh.visual.kind == "vertex" and np.all(mesh.visual.vertex_colors == [255, 0, 0, 255])


def test_materials():
    simple = trimesh.visual.texture.SimpleMaterial(diffuse=[0.5, 0.5, 0.5], Ns=12.0)
    assert np.array_equal(simple.diffuse, [128, 128, 128, 255]) and simple.kwargs == {"Ns": 12.0}
    assert simple.image is None
    pbr = trimesh.visual.texture.PBRMaterial(baseColorFactor=[1.0, 0.5, 0.0, 1.0], metallicFactor=0.1,
                                            alphaMode="BLEND")
    assert np.array_equal(pbr.baseColorFactor, [255, 128, 0, 255]) and pbr.metallicFactor == 0.1
    assert trimesh.visual.material.PBRMaterial is trimesh.visual.texture.PBRMaterial
    with pytest.raises(ValueError):
        trimesh.visual.texture.PBRMaterial(alphaMode="SOMETIMES")
