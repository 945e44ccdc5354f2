"""Mesh.from_trimesh and Scene.from_trimesh_scene read trimesh objects as pyrender does (the stand-in in support/)."""
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import facet
from conftest import look_at

sys.path.insert(0, str(Path(__file__).resolve().parent / "support"))
import trimesh  # noqa: E402


def front_view(mesh, flags=facet.RenderFlags.FLAT, pose=None):
    """The mesh seen head-on from +z, flat (its colours as they are), 64 x 48; (colour, depth)."""
    scene = facet.Scene(bg_color=(0.0, 0.0, 0.0, 1.0))
    scene.add(mesh, pose=pose)
    scene.add(facet.PerspectiveCamera(yfov=0.9, znear=0.1, zfar=20.0), pose=look_at((0, 0, 3)))
    return facet.OffscreenRenderer(64, 48, threads=1, samples=1).render(scene, flags)


def test_an_objs_texture_and_simple_material_come_along(tmp_path):
    """An OBJ with an MTL and a texture: red above, blue below. The texture is drawn with its uvs, and the MTL's
    Phong exponent becomes pyrender's roughness."""
    image = np.zeros((8, 8, 3), np.uint8)
    image[:4] = (255, 0, 0)
    image[4:] = (0, 0, 255)
    Image.fromarray(image).save(tmp_path / "paint.png")
    (tmp_path / "quad.mtl").write_text("newmtl paint\nKd 1 1 1\nNs 30\nmap_Kd paint.png\n")
    (tmp_path / "quad.obj").write_text("mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl paint\nf 1/1 2/2 3/3 4/4\n")
    mesh = facet.Mesh.from_trimesh(trimesh.load(str(tmp_path / "quad.obj")))
    material = mesh.primitives[0].material
    assert material.baseColorTexture is not None and material.alphaMode == "BLEND"
    assert material.roughnessFactor == pytest.approx((2.0 / 32.0) ** 0.25)
    color, _ = front_view(mesh)
    top, bottom = color[14, 32].astype(int), color[34, 32].astype(int)
    assert top[0] > 200 and top[2] < 40 and bottom[2] > 200 and bottom[0] < 40


def test_face_colours_need_flat_faces_and_vertex_colours_are_linear_multipliers():
    box = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    box.visual.face_colors = np.tile([0, 255, 0, 255], (12, 1)).astype(np.uint8)
    with pytest.raises(ValueError, match="smooth=False"):
        facet.Mesh.from_trimesh(box, smooth=True)
    flat_faced = facet.Mesh.from_trimesh(box, smooth=False)
    assert len(flat_faced.primitives[0].positions) == 36  # three vertices of its own per face
    green = front_view(flat_faced)[0][24, 32]
    np.testing.assert_array_equal(green, [0, 255, 0])
    box.visual.vertex_colors = np.array([128, 64, 255, 255], dtype=np.uint8)
    color = front_view(facet.Mesh.from_trimesh(box))[0][24, 32]
    np.testing.assert_array_equal(color, [128, 64, 255])  # FLAT writes them unconverted, as pyrender's flat shader


def test_a_given_material_is_copied_for_each_mesh_of_a_list_and_poses_instance_them():
    material = facet.MetallicRoughnessMaterial(baseColorFactor=[1.0, 0.0, 0.0, 1.0])
    small = trimesh.creation.box(extents=[0.2, 0.2, 0.2])
    poses = np.stack([np.eye(4), np.eye(4)])
    poses[1, 0, 3] = 1.0
    mesh = facet.Mesh.from_trimesh([small, small.copy()], material=material, poses=poses)
    assert len(mesh.primitives) == 2
    first, second = (p.material for p in mesh.primitives)
    assert first is not material and second is not first and first.baseColorFactor[0] == 1.0
    np.testing.assert_allclose(mesh.bounds, [[-0.1, -0.1, -0.1], [1.1, 0.1, 0.1]])
    _, depth = front_view(mesh)
    # The instance one unit to the right, about 16 pixels right of the centre, is drawn too; between them, nothing.
    assert depth[24, 32] > 0 and depth[24, 44:53].max() > 0 and depth[24, 38] == 0
    with pytest.raises(TypeError):
        facet.Mesh.from_trimesh("box.obj")


def test_a_trimesh_scene_is_placed_by_its_graph():
    scene = trimesh.Scene()
    box = trimesh.creation.box(extents=[0.5, 0.5, 0.5])
    left, right = np.eye(4), np.eye(4)
    left[0, 3], right[0, 3] = -1.0, 1.0
    scene.add_geometry(box, geom_name="box", transform=left)
    scene.add_geometry(box, geom_name="box", transform=right)
    placed = facet.Scene.from_trimesh_scene(scene, bg_color=[0.0, 0.0, 0.0])
    assert len(placed.mesh_nodes) == 2
    np.testing.assert_allclose(placed.bounds, [[-1.25, -0.25, -0.25], [1.25, 0.25, 0.25]])
    np.testing.assert_allclose(placed.bg_color, [0.0, 0.0, 0.0, 1.0])
