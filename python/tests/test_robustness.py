"""test_robustness.py - bad input raises the right exception; memory stays flat; threads render in parallel."""
import threading

import numpy as np
import pytest

import facet
from conftest import look_at, rss_bytes, uv_sphere

TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)


@pytest.mark.parametrize("make, message", [
    (lambda: facet.Mesh(np.zeros((3, 2)), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh(np.zeros(9), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh(np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh(np.array([[0, 0, np.inf], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, 3]]), "faces"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, -1]]), "faces"),
    (lambda: facet.Mesh(TRIANGLE, [[0.0, 1.0, 2.0]]), "faces"),
    (lambda: facet.Mesh(TRIANGLE, np.zeros((0, 3), dtype=int)), "faces"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, 2]], normals=np.zeros((2, 3))), "normals"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, 2]], colors=np.full((3, 3), 2.0)), "colors"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, 2]], texture=np.zeros((4, 4, 3), dtype=np.uint8)), "uvs"),
    (lambda: facet.Mesh(TRIANGLE, [[0, 1, 2]], uvs=np.zeros((3, 2)), texture=np.zeros((4, 4, 5))), "texture"),
    (lambda: facet.Mesh(np.array([["a", "b", "c"]] * 3), [[0, 1, 2]]), "positions"),
    (lambda: facet.OffscreenRenderer(0, 10), "size"),
    (lambda: facet.OffscreenRenderer(20000, 10), "size"),
    (lambda: facet.OffscreenRenderer(10, 10, samples=3), "samples"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", samples=16), "samples"),
    (lambda: facet.PerspectiveCamera(yfov=0), "yfov"),
    (lambda: facet.PerspectiveCamera(yfov=1, znear=0), "znear"),
    (lambda: facet.IntrinsicsCamera(0, 1, 0, 0), "fx"),
    (lambda: facet.OrthographicCamera(1, 1, znear=2, zfar=1), "zfar"),
    (lambda: facet.Scene().add(facet.Mesh(TRIANGLE, [[0, 1, 2]]), pose=np.eye(3)), "pose"),
    (lambda: facet.Scene().add(facet.Mesh(TRIANGLE, [[0, 1, 2]]), pose=np.full((4, 4), np.nan)), "pose"),
    (lambda: facet.Scene().add("not a mesh"), "str"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", width=0), "width"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", buffers=["colour"]), "colour"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", projection="fisheye"), "fisheye"),
])
def test_bad_arrays_and_arguments_raise_value_error(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_a_scene_without_camera_cannot_render():
    scene = facet.Scene()
    scene.add(facet.Mesh(TRIANGLE, [[0, 1, 2]]))
    with pytest.raises(ValueError, match="camera"):
        facet.OffscreenRenderer(8, 8).render(scene)


def test_missing_and_malformed_files_raise_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.glb: no such file"):
        facet.Mesh.from_file(tmp_path / "nope.glb")
    bad = tmp_path / "bad.ply"
    bad.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 99999999999\nend_header\n1 2 3\n")
    for load in (facet.Mesh.from_file, facet.Scene.from_file, lambda p: facet.render(p)):
        with pytest.raises(OSError, match="bad.ply"):
            load(bad)
        with pytest.raises(facet.LoadError):
            load(bad)
    with pytest.raises(OSError, match="not a regular file"):
        facet.Mesh.from_file(tmp_path)
    with pytest.raises(OSError, match="pond.0.ply"):
        facet.Scene.from_file("/usr/share/assimp/models/PLY/pond.0.ply")


def test_memory_stays_flat_over_a_thousand_renders():
    positions, faces, normals = uv_sphere(rings=32, segments=64)
    scene = facet.Scene()
    scene.add(facet.Mesh(positions, faces, normals=normals))
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 4)))
    renderer = facet.OffscreenRenderer(64, 48, threads=1)
    for _ in range(100):
        renderer.render_buffers(scene, facet.BUFFERS)
    before = rss_bytes()
    for _ in range(1000):
        out = renderer.render_buffers(scene, facet.BUFFERS)
        assert out["mask"].any()
    grown = rss_bytes() - before
    assert grown < 4 * 1024 * 1024, f"resident memory grew by {grown} bytes over 1,000 renders"


def test_rendering_releases_the_gil():
    """While one thread renders, Python code in another keeps running: the GIL is released inside render, so
    renderers in different threads draw in parallel. Counted, not timed: with the GIL held through the call, the
    other thread could not run at all while the flag is up."""
    positions, faces, normals = uv_sphere(rings=160, segments=320)  # about 100,000 triangles
    scene = facet.Scene()
    scene.add(facet.Mesh(positions, faces, normals=normals))
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 3)))
    renderer = facet.OffscreenRenderer(320, 240, threads=1)
    renderer.render(scene)  # warm up: the first render prepares the mesh
    rendering = threading.Event()
    finished = threading.Event()

    def work():
        for _ in range(10):
            rendering.set()
            renderer.render(scene)
            rendering.clear()
        finished.set()

    worker = threading.Thread(target=work)
    worker.start()
    ticks = 0
    while not finished.is_set():
        if rendering.is_set():
            ticks += 1
    worker.join()
    assert ticks > 100, f"the main thread ran {ticks} times during ten renders"
