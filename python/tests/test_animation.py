"""test_animation.py - a glTF file's animation through facet.render: the pose and the motion buffer against numpy's own
reading of the file, skinning and projection."""
import base64
import json

import numpy as np
import pytest

import facet

MODELS = "/usr/share/assimp/models/glTF2"
SKIN = f"{MODELS}/simple_skin/simple_skin.gltf"
STILL = f"{MODELS}/BoxTextured-glTF/BoxTextured.gltf"


class Gltf:
    """The file read with json and numpy alone: its accessors as arrays, its nodes posed by its first animation."""

    def __init__(self, path):
        self.json = json.load(open(path))
        self.buffers = [base64.b64decode(b["uri"].split(",", 1)[1]) for b in self.json["buffers"]]

    def accessor(self, index):
        a = self.json["accessors"][index]
        view = self.json["bufferViews"][a["bufferView"]]
        dtype = {5126: np.float32, 5123: np.uint16, 5121: np.uint8}[a["componentType"]]
        width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}[a["type"]]
        item = np.dtype(dtype).itemsize * width
        stride = view.get("byteStride", item)
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        raw = self.buffers[view["buffer"]]
        rows = [np.frombuffer(raw, dtype, width, start + i * stride) for i in range(a["count"])]
        return np.array(rows, dtype=np.float64)

    def rotation_at(self, node, t):
        """The node's rotation at t: its channel's keys slerped (and normalised), or its own."""
        for channel in self.json["animations"][0]["channels"]:
            if channel["target"] == {"node": node, "path": "rotation"}:
                sampler = self.json["animations"][0]["samplers"][channel["sampler"]]
                times, values = self.accessor(sampler["input"])[:, 0], self.accessor(sampler["output"])
                k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2))
                u = float(np.clip((t - times[k]) / (times[k + 1] - times[k]), 0, 1))
                a, b = values[k], values[k + 1]
                if a @ b < 0:
                    b = -b
                angle = np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))
                q = a * (1 - u) + b * u if angle < 1e-6 else \
                    (np.sin((1 - u) * angle) * a + np.sin(u * angle) * b) / np.sin(angle)
                return q / np.linalg.norm(q)
        return np.array(self.json["nodes"][node].get("rotation", [0, 0, 0, 1]), dtype=np.float64)

    def world(self, node, t):
        n = self.json["nodes"][node]
        x, y, z, w = self.rotation_at(node, t)
        local = np.eye(4)
        local[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
        local[:3, :3] *= n.get("scale", [1, 1, 1])
        local[:3, 3] = n.get("translation", [0, 0, 0])
        parents = [i for i, p in enumerate(self.json["nodes"]) if node in p.get("children", [])]
        return self.world(parents[0], t) @ local if parents else local

    def skinned(self, t):
        """Every vertex of mesh 0 skinned at t: the sum of its weights times joint world times inverse bind."""
        attributes = self.json["meshes"][0]["primitives"][0]["attributes"]
        positions = self.accessor(attributes["POSITION"])
        joints = self.accessor(attributes["JOINTS_0"]).astype(int)
        weights = self.accessor(attributes["WEIGHTS_0"])
        skin = self.json["skins"][0]
        binds = self.accessor(skin["inverseBindMatrices"]).reshape(-1, 4, 4).transpose(0, 2, 1)  # column-major
        matrices = np.array([self.world(j, t) @ binds[k] for k, j in enumerate(skin["joints"])])
        homogeneous = np.c_[positions, np.ones(len(positions))]
        blended = np.einsum("vk,vkij->vij", weights, matrices[joints])
        return np.einsum("vij,vj->vi", blended, homogeneous)[:, :3]

    def triangles(self):
        return self.accessor(self.json["meshes"][0]["primitives"][0]["indices"])[:, 0].astype(int).reshape(-1, 3)


def project(camera, points):
    """Pixels (x right, y down) of world points through the camera facet.render returns (OpenCV K and pose)."""
    camera_from_world = np.array(camera["camera_from_world"])
    seen = (camera_from_world @ np.c_[points, np.ones(len(points))].T)[:3]
    pixels = np.array(camera["K"]) @ seen
    return (pixels[:2] / pixels[2]).T


def test_the_motion_buffer_is_where_numpys_skinned_points_go():
    gltf = Gltf(SKIN)
    t, fps = 0.7, 30.0
    out = facet.render(SKIN, 160, 120, buffers=["mask", "motion"], time=t, fps=fps)
    motion, mask = out["motion"], out["mask"] > 0
    assert motion.shape == (120, 160, 2) and motion.dtype == np.float32
    # Each triangle's centroid, skinned at t and a frame later, projected at both moments.
    corners = gltf.triangles()
    start = project(out["camera"], gltf.skinned(t)[corners].mean(axis=1))
    end = project(out["camera"], gltf.skinned(t + 1 / fps)[corners].mean(axis=1))
    checked = 0
    for (u, v), want in zip(start, end - start):
        x, y = int(round(u)), int(round(v))
        if not mask[y - 2:y + 3, x - 2:x + 3].all():
            continue  # too near the silhouette for the pixel's neighbours to share the centroid's triangle
        assert np.abs(motion[y, x] - want).max() < 0.1, (x, y, motion[y, x], want)
        checked += 1
    assert checked >= 4
    assert np.abs(end - start).max() > 0.5  # the skin does move in this frame


def test_time_poses_the_model_and_motion_is_zero_where_nothing_moves():
    rest = facet.render(SKIN, 96, 72, buffers=["color"])["color"]
    bent = facet.render(SKIN, 96, 72, buffers=["color"], time=1.25, animation=0)["color"]
    by_name_or_index = facet.render(SKIN, 96, 72, buffers=["color"], time=1.25, animation="0")["color"]
    assert (rest != bent).any() and (bent == by_name_or_index).all()
    still = facet.render(STILL, 64, 48, buffers=["motion", "mask"])
    assert (still["mask"] > 0).any() and not still["motion"].any()


def test_bad_animation_requests_raise_clear_errors():
    with pytest.raises(facet.LoadError, match="has no animation 'Walk'"):
        facet.render(SKIN, 32, 24, time=1.0, animation="Walk")
    with pytest.raises(facet.LoadError, match="has no animation to play"):
        facet.render(STILL, 32, 24, time=1.0)
    with pytest.raises(ValueError, match="time"):
        facet.render(SKIN, 32, 24, time=float("nan"))
    with pytest.raises(ValueError, match="fps"):
        facet.render(SKIN, 32, 24, time=1.0, fps=0)
    scene = facet.Scene.from_file(STILL)
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=np.array(
        [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 3], [0, 0, 0, 1]], dtype=float))
    with pytest.raises(ValueError, match="motion"):
        facet.OffscreenRenderer(32, 24).render_buffers(scene, ["motion"])


def test_a_scene_read_from_a_file_is_posed_by_set_time():
    gltf = Gltf(SKIN)
    scene = facet.Scene.from_file(SKIN)
    assert scene.animations == [("", 5.5)]
    (node,) = [n for n in scene.mesh_nodes]
    primitive = node.mesh.primitives[0]
    # Unanimated, and at the times set: the mesh's box is numpy's skinned vertices' box.
    np.testing.assert_allclose(primitive.bounds, [gltf.skinned(0).min(0), gltf.skinned(0).max(0)], atol=1e-5)
    eye = np.eye(4)
    eye[:3, 3] = [0.5, 1, 4]
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=eye)
    renderer = facet.OffscreenRenderer(96, 72)
    rest, _ = renderer.render(scene)
    for t in (0.7, 2.25, 4.0):
        scene.set_time(t)
        np.testing.assert_allclose(primitive.bounds, [gltf.skinned(t).min(0), gltf.skinned(t).max(0)], atol=1e-5)
    scene.set_time(0.7, animation=0)
    bent, _ = renderer.render(scene)
    assert (rest != bent).any()
    scene.set_time(0.0)
    assert (renderer.render(scene)[0] == rest).all()
    with pytest.raises(facet.LoadError, match="has no animation 'Walk'"):
        scene.set_time(1.0, animation="Walk")
    with pytest.raises(ValueError, match="time"):
        scene.set_time(float("inf"))
    with pytest.raises(ValueError, match="no animation to play"):
        facet.Scene.from_file(STILL).set_time(1.0)
    assert facet.Scene().animations == []


def test_motion_between_two_camera_poses_is_where_each_surface_point_goes():
    """A still model seen from two azimuths: each pixel's point, found from the depth buffer through the first
    camera, projected through the second (numpy's own unprojection and projection)."""
    first = facet.render(STILL, 96, 72, buffers=["depth", "motion"], motion_azimuth=6.0, motion_elevation=-3.0)
    second = facet.render(STILL, 96, 72, buffers=["depth"], azimuth=6.0, elevation=-3.0)
    depth, motion = first["depth"], first["motion"]
    k = np.array(first["camera"]["K"])
    world_from_camera = np.linalg.inv(np.array(first["camera"]["camera_from_world"]))
    ys, xs = np.nonzero(depth > 0)
    seen = np.stack([(xs - k[0, 2]) / k[0, 0] * depth[ys, xs], (ys - k[1, 2]) / k[1, 1] * depth[ys, xs],
                     depth[ys, xs]], axis=1)
    points = (world_from_camera @ np.c_[seen, np.ones(len(seen))].T).T[:, :3]
    want = project(second["camera"], points) - np.stack([xs, ys], axis=1)
    assert np.abs(motion[ys, xs] - want).max() < 0.05
    assert np.abs(want).max() > 1.0
    # Between two times too: the skin from 0.7 s to 1.0 s moves three times as far as a frame at 10 a second.
    a = facet.render(SKIN, 96, 72, buffers=["motion"], time=0.7, motion_time=1.0)["motion"]
    b = facet.render(SKIN, 96, 72, buffers=["motion"], time=0.7, fps=10)["motion"]
    assert np.abs(a).max() > 2 * np.abs(b).max() > 0
