"""Nodes, scenes, primitives and meshes behave as pyrender's do: the tree, transforms, checks and bounds."""
import math

import numpy as np
import pytest

import facet


def quaternion(axis, angle):
    """(x, y, z, w) of a rotation by angle about axis."""
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return np.append(axis * math.sin(angle / 2.0), math.cos(angle / 2.0))


def rotation(axis, angle):
    """Rodrigues' formula, independently of the quaternion code under test."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    m = np.eye(4)
    m[:3, :3] = np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * cross @ cross
    return m


def translation(t):
    m = np.eye(4)
    m[:3, 3] = t
    return m


def box(half=0.5):
    corners = np.array([[x, y, z] for x in (-half, half) for y in (-half, half) for z in (-half, half)], dtype=float)
    faces = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1], [2, 3, 7], [2, 7, 6], [0, 2, 6],
             [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return facet.Primitive(positions=corners, indices=faces)


def test_a_new_node_is_empty_and_at_the_origin():
    n = facet.Node()
    assert (n.name, n.camera, n.mesh, n.light, n.skin, n.weights) == (None,) * 6
    assert n.children == []
    np.testing.assert_array_equal(n.matrix, np.eye(4))
    np.testing.assert_array_equal(n.rotation, [0, 0, 0, 1])


@pytest.mark.parametrize("axis,angle", [((1, 0, 0), math.pi / 2), ((0, 1, 0), 2.5), ((1, 1, 1), -1.0),
                                        ((0, 0, 1), math.pi)])
def test_matrix_and_translation_rotation_scale_stay_consistent(axis, angle):
    scale = np.array([0.5, 2.0, 3.0])
    m = translation([1, -2, 3]) @ rotation(axis, angle) @ np.diag(np.append(scale, 1.0))
    n = facet.Node(matrix=m)
    np.testing.assert_allclose(n.translation, [1, -2, 3], atol=1e-12)
    np.testing.assert_allclose(n.scale, scale, atol=1e-12)
    q = quaternion(axis, angle)
    assert np.allclose(n.rotation, q) or np.allclose(n.rotation, -q)
    # Setting one part rebuilds the matrix from the three.
    n.translation = [0, 0, 0]
    np.testing.assert_allclose(n.matrix, rotation(axis, angle) @ np.diag(np.append(scale, 1.0)), atol=1e-12)
    n.rotation = quaternion((0, 0, 1), math.pi / 2)
    np.testing.assert_allclose(n.matrix[:3, 0], [0, 0.5, 0], atol=1e-12)


def test_the_matrix_is_a_copy_and_bad_transforms_raise():
    n = facet.Node()
    n.matrix[0, 0] = 7.0
    assert n.matrix[0, 0] == 1.0
    for bad in (np.eye(3), 2 * np.eye(4), np.full((4, 4), np.nan)):
        with pytest.raises(ValueError):
            n.matrix = bad
    with pytest.raises(ValueError):
        n.rotation = [1, 2, 3, 4]  # not a unit quaternion
    with pytest.raises(ValueError):
        n.translation = [1, 2]
    with pytest.raises(TypeError):
        n.mesh = facet.DirectionalLight()
    with pytest.raises(TypeError):
        n.camera = facet.Mesh([])


def test_pyrender_defaults_and_empty_scene_values():
    s = facet.Scene()
    np.testing.assert_array_equal(s.bg_color, np.ones(4))
    np.testing.assert_array_equal(s.ambient_light, np.zeros(3))
    assert s.nodes == set() and s.meshes == set() and s.main_camera_node is None
    np.testing.assert_array_equal(s.bounds, np.zeros((2, 3)))
    assert s.scale == 0
    np.testing.assert_allclose(facet.Scene(bg_color=[0, 255, 0]).bg_color, [0, 1, 0, 1])


def test_poses_compose_down_the_tree_and_set_pose_sets_the_local_matrix():
    a, b, c = facet.Node(matrix=translation([1, 0, 0])), facet.Node(matrix=rotation((0, 0, 1), math.pi / 2)), \
        facet.Node(matrix=translation([0, 2, 0]))
    a.children.append(b)
    b.children.append(c)
    s = facet.Scene(nodes=[a, b, c])
    assert s.nodes == {a, b, c}
    np.testing.assert_allclose(s.get_pose(c)[:3, 3], [-1, 0, 0], atol=1e-12)
    s.set_pose(a, translation([0, 0, 5]))
    np.testing.assert_allclose(s.get_pose(c)[:3, 3], [-2, 0, 5], atol=1e-12)
    with pytest.raises(ValueError):
        s.get_pose(facet.Node())


def test_a_node_with_two_parents_or_added_twice_is_refused():
    a, b, c = facet.Node(), facet.Node(), facet.Node()
    a.children.append(c)
    b.children.append(c)
    with pytest.raises(ValueError):
        facet.Scene(nodes=[a, b, c])
    s = facet.Scene()
    s.add_node(a)
    with pytest.raises(ValueError):
        s.add_node(c)  # came in with a
    with pytest.raises(ValueError):
        s.add_node(facet.Node(), parent_node=b)  # b is not in the scene


def test_removing_a_node_removes_its_tree_and_detaches_it():
    a, b, c = facet.Node(), facet.Node(), facet.Node()
    a.children.append(b)
    b.children.append(c)
    s = facet.Scene(nodes=[a])
    s.remove_node(b)
    assert s.nodes == {a} and a.children == [] and b.children == [c]
    s.add_node(b, parent_node=a)
    assert s.nodes == {a, b, c} and a.children == [b]


def test_add_finds_parents_by_name_and_sorts_what_it_holds():
    s = facet.Scene()
    mesh = facet.Mesh([box()], name="cube")
    spot = s.add(facet.SpotLight(), name="spot")
    point = s.add(facet.PointLight(), parent_name="spot")
    sun = s.add(facet.DirectionalLight(), parent_node=point)
    first = s.add(mesh, name="m")
    second = s.add(mesh, pose=translation([2, 0, 0]))
    ortho, persp = s.add(facet.OrthographicCamera(1, 1)), s.add(facet.PerspectiveCamera(yfov=1.0))
    assert spot.children == [point] and point.children == [sun]
    assert s.point_light_nodes == {point} and s.spot_light_nodes == {spot} and s.directional_light_nodes == {sun}
    assert s.mesh_nodes == {first, second} and s.meshes == {mesh}
    assert s.get_nodes(obj=mesh) == {first, second} and s.get_nodes(obj_name="cube", name="m") == {first}
    assert s.main_camera_node is ortho
    s.main_camera_node = persp
    s.remove_node(persp)
    assert s.main_camera_node is ortho
    with pytest.raises(ValueError):
        s.main_camera_node = first  # not a camera
    s.add(mesh, name="twin")
    s.add(mesh, name="twin")
    with pytest.raises(ValueError):
        s.add(mesh, parent_name="twin")  # two nodes of that name
    with pytest.raises(ValueError):
        s.add(mesh, parent_name="nobody")
    with pytest.raises(TypeError):
        s.add("a string")
    s.clear()
    assert s.nodes == set() and s.main_camera_node is None


def test_scene_bounds_follow_the_tree_and_instances():
    s = facet.Scene()
    a = s.add(facet.Mesh([box()]))
    b = s.add(facet.Mesh([box()]), pose=translation([1, 0, 0]), parent_node=a)
    np.testing.assert_allclose(s.bounds, [[-0.5, -0.5, -0.5], [1.5, 0.5, 0.5]])
    s.set_pose(a, translation([0, 0, 1]))
    np.testing.assert_allclose(s.bounds, [[-0.5, -0.5, 0.5], [1.5, 0.5, 1.5]])
    s.remove_node(b)
    poses = np.stack([translation([0, 0, 0]), translation([0, 3, 0])])
    s.add(facet.Mesh([facet.Primitive(positions=box().positions, indices=box().indices, poses=poses)]))
    np.testing.assert_allclose(s.bounds, [[-0.5, -0.5, -0.5], [0.5, 3.5, 1.5]])
    assert s.extents[1] == pytest.approx(4.0)


def test_primitive_checks_arrays_and_reports_transparency():
    p = box()
    assert p.mode == facet.GLTF.TRIANGLES and isinstance(p.material, facet.MetallicRoughnessMaterial)
    for name, bad in (("normals", np.zeros(8)), ("tangents", np.zeros((8, 3))), ("texcoord_0", np.zeros((7, 2))),
                      ("color_0", np.zeros((7, 4)))):
        with pytest.raises(ValueError, match=name):
            setattr(p, name, bad)
    with pytest.raises(TypeError):
        p.material = "red"
    with pytest.raises(ValueError):
        facet.Primitive([], mode=7)
    with pytest.raises(ValueError):
        p.poses = np.eye(3)
    assert not p.is_transparent
    p.color_0 = np.array([255, 0, 0, 128], dtype=np.uint8)  # one colour for every vertex
    assert p.color_0.shape == (8, 4) and p.color_0[0, 3] == pytest.approx(128 / 255) and p.is_transparent
    p.color_0 = None
    p.material.alphaMode = "BLEND"
    p.material.baseColorFactor = [1, 1, 1, 0.5]
    assert p.is_transparent


def test_mesh_bounds_and_counts_over_primitives():
    mesh = facet.Mesh([box(), facet.Primitive(positions=[[0, 0, 2], [1, 0, 2], [0, 1, 2]])])
    np.testing.assert_allclose(mesh.bounds, [[-0.5, -0.5, -0.5], [1, 1, 2]])
    np.testing.assert_allclose(mesh.centroid, [0.25, 0.25, 0.75])
    assert mesh.triangle_count == 13 and mesh.is_visible and mesh.name is None
    with pytest.raises(TypeError):
        facet.Mesh()
    with pytest.raises(TypeError):
        facet.Mesh([np.zeros((3, 3))])


def test_cameras_check_their_values_as_pyrender_does():
    p = facet.PerspectiveCamera(yfov=1.0)
    assert (p.znear, p.zfar, p.aspectRatio) == (0.05, None, None)
    for attr, bad in (("yfov", 0.0), ("znear", -1.0), ("aspectRatio", 0.0)):
        with pytest.raises(ValueError):
            setattr(p, attr, bad)
    with pytest.raises(ValueError):
        p.zfar = 0.05  # not beyond znear
    with pytest.raises(ValueError):
        p.get_projection_matrix()  # no size, no aspect ratio
    infinite = p.get_projection_matrix(4, 2)
    assert infinite[2, 2] == -1.0 and infinite[2, 3] == pytest.approx(-0.1)
    p.aspectRatio, p.zfar = 2.0, 10.0
    np.testing.assert_allclose(p.get_projection_matrix(), p.get_projection_matrix(100, 100))
    near_clip = p.get_projection_matrix() @ [0, 0, -0.05, 1]
    far_clip = p.get_projection_matrix() @ [0, 0, -10.0, 1]
    assert near_clip[2] / near_clip[3] == pytest.approx(-1) and far_clip[2] / far_clip[3] == pytest.approx(1)
    o = facet.OrthographicCamera(xmag=1.0, ymag=2.0)
    with pytest.raises(TypeError):
        o.xmag = None
    with pytest.raises(ValueError):
        o.znear = 0.0  # a parallel projection needs a positive near plane


def test_lights_check_their_values_and_describe_their_shadow_cameras():
    d = facet.DirectionalLight()
    np.testing.assert_array_equal(d.color, np.ones(3))
    with pytest.raises(ValueError):
        d.color = None
    with pytest.raises(TypeError):
        d.intensity = None
    camera = d._get_shadow_camera(scene_scale=3.0)
    assert isinstance(camera, facet.OrthographicCamera) and camera.xmag == 3.0 and camera.zfar == 30.0
    d._generate_shadow_texture()
    assert isinstance(d.shadow_texture, facet.Texture) and d.shadow_texture.width == 2048
    s = facet.SpotLight(outerConeAngle=0.5)
    with pytest.raises(ValueError):
        s.innerConeAngle = 0.6  # beyond the outer cone
    with pytest.raises(ValueError):
        s.outerConeAngle = 2.0
    with pytest.raises(ValueError):
        s.range = 0.0
    assert s._get_shadow_camera(1.0).yfov == pytest.approx(1.0 + math.pi / 16)
    with pytest.raises(NotImplementedError):
        facet.PointLight()._get_shadow_camera(1.0)


def test_render_flags_with_unknown_bits_raise():
    assert facet.RenderFlags.SHADOWS_ALL == 224 and facet.RenderFlags.SEG == 8192
    from facet.constants import render_flags
    assert render_flags(2 | 1024) == facet.RenderFlags.OFFSCREEN | facet.RenderFlags.SKIP_CULL_FACES
    for bad in (1 << 14, -1, 3.0):
        with pytest.raises(ValueError):
            render_flags(bad)
