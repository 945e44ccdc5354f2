"""test_robustness.py - bad input raises the right exception; memory stays flat; threads render in parallel."""
import json
import struct
import threading
import zlib

import numpy as np
import pytest

import facet
from conftest import look_at, rss_bytes, uv_sphere

TRIANGLE = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=float)


@pytest.mark.parametrize("make, message", [
    (lambda: facet.Mesh.from_arrays(np.zeros((3, 2)), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh.from_arrays(np.zeros(9), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh.from_arrays(np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh.from_arrays(np.array([[0, 0, np.inf], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]]), "positions"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 3]]), "faces"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, -1]]), "faces"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0.0, 1.0, 2.0]]), "faces"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, np.zeros((0, 3), dtype=int)), "faces"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]], normals=np.zeros((2, 3))), "normals"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]], colors=np.full((3, 3), 2.0)), "colors"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]], texture=np.zeros((4, 4, 3), dtype=np.uint8)), "uvs"),
    (lambda: facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]], uvs=np.zeros((3, 2)), texture=np.zeros((4, 4, 5))), "texture"),
    (lambda: facet.Mesh.from_arrays(np.array([["a", "b", "c"]] * 3), [[0, 1, 2]]), "positions"),
    (lambda: facet.OffscreenRenderer(0, 10), "size"),
    (lambda: facet.OffscreenRenderer(20000, 10), "size"),
    (lambda: facet.OffscreenRenderer(10, 10, samples=3), "samples"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", samples=16), "samples"),
    (lambda: facet.PerspectiveCamera(yfov=0), "yfov"),
    (lambda: facet.PerspectiveCamera(yfov=1, znear=-1), "znear"),
    (lambda: facet.IntrinsicsCamera(0, 1, 0, 0), "fx"),
    (lambda: facet.OrthographicCamera(1, 1, znear=2, zfar=1), "zfar"),
    (lambda: facet.Scene().add(facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]]), pose=np.eye(3)), "pose"),
    (lambda: facet.Scene().add(facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]]), pose=np.full((4, 4), np.nan)), "pose"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", width=0), "width"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", buffers=["colour"]), "colour"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", projection="fisheye"), "fisheye"),
    # Unknown names are reported with the names the library knows, as the CLI spells them.
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", shading="toon"), "toon.*blinn-phong"),
    (lambda: facet.render("/usr/share/assimp/models/OBJ/box.obj", buffers=["rgb"]), "rgb.*color, depth"),
])
def test_bad_arrays_and_arguments_raise_value_error(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_shading_names_are_the_clis_and_the_old_spelling_still_works():
    box = "/usr/share/assimp/models/OBJ/box.obj"
    new = facet.render(box, width=32, height=24, shading="blinn-phong", buffers=["color"])["color"]
    old = facet.render(box, width=32, height=24, shading="blinn_phong", buffers=["color"])["color"]
    own = facet.render(box, width=32, height=24, buffers=["color"])["color"]
    assert np.array_equal(new, old)
    assert not np.array_equal(new, own)


def test_a_scene_without_camera_cannot_render():
    scene = facet.Scene()
    scene.add(facet.Mesh.from_arrays(TRIANGLE, [[0, 1, 2]]))
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


BOX = "/usr/share/assimp/models/OBJ/box.obj"  # 12 triangles
# Every way Python reads a model file, each taking the load limits as keywords.
LOADS = {
    "Mesh.from_file": facet.Mesh.from_file,
    "Scene.from_file": facet.Scene.from_file,
    "render": lambda path, **limits: facet.render(path, width=32, height=24, buffers=["color"], **limits),
}


@pytest.mark.parametrize("load", LOADS.values(), ids=LOADS.keys())
@pytest.mark.parametrize("limits, message", [
    ({"max_triangles": 0}, "max_triangles: expected 1..1099511627776, got 0"),
    ({"max_triangles": 2**70}, "max_triangles: expected 1..1099511627776, got 1180591620717411303424"),
    ({"max_triangles": 1.5}, "max_triangles: expected an integer"),
    ({"max_points": 0}, "max_points: expected 1..1099511627776, got 0"),
    ({"max_texture_size": 0}, "max_texture_size: expected 1..16384, got 0"),
    ({"max_texture_size": 16385}, "max_texture_size: expected 1..16384, got 16385"),
])
def test_load_limits_out_of_range_raise_value_error(load, limits, message):
    with pytest.raises(ValueError, match=message):
        load(BOX, **limits)


@pytest.mark.parametrize("load", LOADS.values(), ids=LOADS.keys())
def test_a_model_over_the_triangle_limit_is_refused(load):
    load(BOX, max_triangles=12)
    # The message names the keyword that lifts the limit, not the CLI's flag.
    with pytest.raises(facet.LoadError,
                       match=r"box.obj: places 12 triangles, more than the limit of 11 \(keyword max_triangles\)"):
        load(BOX, max_triangles=11)


@pytest.mark.parametrize("load", LOADS.values(), ids=LOADS.keys())
def test_a_cloud_over_the_point_limit_is_refused(load, tmp_path):
    cloud = tmp_path / "cloud.xyz"
    np.savetxt(cloud, np.random.default_rng(3).random((30, 3)))
    load(cloud, max_points=30)
    with pytest.raises(facet.LoadError,
                       match=r"cloud.xyz: places 30 points and splats, more than the limit of 29 \(keyword max_points\)"):
        load(cloud, max_points=29)


@pytest.mark.parametrize("load", LOADS.values(), ids=LOADS.keys())
def test_files_outside_the_model_folder_are_read_only_when_allowed(load, tmp_path):
    (tmp_path / "outside.bin").write_bytes(np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], dtype="<f4").tobytes())
    model = tmp_path / "model" / "climbs.gltf"
    model.parent.mkdir()
    model.write_text(json.dumps({
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "buffers": [{"uri": "../outside.bin", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}]}))
    with pytest.raises(facet.LoadError, match="climbs.gltf"):
        load(model)
    load(model, allow_external_files=True)


def _png(path, width, height):
    """An opaque grey RGBA PNG, written with the standard library."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\0" + bytes([200, 200, 200, 255]) * width for _ in range(height))
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
                     chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


@pytest.mark.parametrize("load", LOADS.values(), ids=LOADS.keys())
def test_textures_over_the_size_limit_are_not_decoded(load, tmp_path, capfd):
    _png(tmp_path / "big.png", 64, 64)
    (tmp_path / "big.mtl").write_text("newmtl m\nKd 1 1 1\nmap_Kd big.png\n")
    model = tmp_path / "big.obj"
    model.write_text("mtllib big.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n")
    load(model, max_texture_size=64)
    assert "over the limit" not in capfd.readouterr().err
    load(model, max_texture_size=32)
    assert "is 64x64 texels, over the limit of 32 a side" in capfd.readouterr().err


def test_memory_stays_flat_over_a_thousand_renders():
    positions, faces, normals = uv_sphere(rings=32, segments=64)
    scene = facet.Scene()
    scene.add(facet.Mesh.from_arrays(positions, faces, normals=normals))
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
    scene.add(facet.Mesh.from_arrays(positions, faces, normals=normals))
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
