"""test_render.py - the Python API's shapes and dtypes, depth, projection, buffers and scenes."""
import numpy as np
import pytest

import facet
from conftest import look_at, uv_sphere

MODELS = "/usr/share/assimp/models"


def sphere_scene(sphere, camera, pose, **kwargs):
    positions, faces, normals = sphere
    scene = facet.Scene(**kwargs)
    scene.add(facet.Mesh.from_arrays(positions, faces, normals=normals))
    scene.add(camera, pose=pose)
    return scene


@pytest.mark.parametrize("dtype", [np.float32, np.float64, np.int32])
@pytest.mark.parametrize("order", ["C", "F"])
def test_any_numeric_dtype_and_order_makes_the_same_image(dtype, order):
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]])
    faces = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint16)
    scene = facet.Scene()
    scene.add(facet.Mesh.from_arrays(np.array(positions, dtype=dtype, order=order), np.array(faces, order=order)))
    scene.add(facet.PerspectiveCamera(yfov=1.0), pose=look_at((0, 0, 3)))
    color, depth = facet.OffscreenRenderer(40, 30, threads=1).render(scene)
    assert color.shape == (30, 40, 3) and color.dtype == np.uint8
    assert depth.shape == (30, 40) and depth.dtype == np.float32
    assert depth[15, 20] == pytest.approx(3.0, rel=1e-5)
    assert (depth > 0).sum() > 100


def test_shapes_and_dtypes_of_every_buffer(sphere):
    scene = sphere_scene(sphere, facet.PerspectiveCamera(yfov=0.8), look_at((0, 0, 4)))
    out = facet.OffscreenRenderer(64, 48, threads=1).render_buffers(scene, facet.BUFFERS)
    assert set(out) == set(facet.BUFFERS)
    assert out["color"].shape == (48, 64, 3) and out["color"].dtype == np.uint8
    assert out["depth"].shape == (48, 64) and out["depth"].dtype == np.float32
    assert out["normal"].shape == (48, 64, 3) and out["normal"].dtype == np.float32
    assert out["ids"].shape == (48, 64, 2) and out["ids"].dtype == np.uint32
    assert out["mask"].shape == (48, 64) and out["mask"].dtype == np.uint8
    # numpy owns the buffers it was handed: writable, and no copy behind them.
    assert out["depth"].flags.writeable and out["depth"].base is not None


def test_sphere_depth_matches_the_analytic_sphere(sphere):
    eye = np.array([0.3, 0.2, 3.5])
    width, height, yfov = 160, 120, 0.9
    scene = sphere_scene(sphere, facet.PerspectiveCamera(yfov=yfov, znear=0.5, zfar=10.0), look_at(eye))
    depth = facet.OffscreenRenderer(width, height, threads=1, samples=1).render(scene, facet.RenderFlags.DEPTH_ONLY)
    pose = look_at(eye)
    # The ray through each pixel centre, in camera space (OpenGL axes), meets the unit sphere at distance t.
    tan = np.tan(yfov / 2)
    ys, xs = np.mgrid[0:height, 0:width]
    ndc_x = (xs + 0.5) / width * 2 - 1
    ndc_y = 1 - (ys + 0.5) / height * 2
    direction_camera = np.stack([ndc_x * tan * width / height, ndc_y * tan, -np.ones_like(ndc_x)], axis=-1)
    direction = direction_camera @ pose[:3, :3].T
    a = (direction ** 2).sum(-1)
    b = 2 * (direction @ eye)
    c = eye @ eye - 1.0
    disc = b * b - 4 * a * c
    t = (-b - np.sqrt(np.maximum(disc, 0))) / (2 * a)
    analytic = t  # the ray's camera-space z component is -1 per unit t, so t is the eye-space depth
    inside = disc > 0.02 * b * b  # away from the silhouette, where tessellation moves the edge
    assert inside.sum() > 2000
    assert np.all(depth[inside] > 0)
    relative = np.abs(depth[inside] - analytic[inside]) / analytic[inside]
    assert relative.max() < 1e-3
    assert np.all(depth[disc < 0] == 0)


def test_orthographic_depth_is_the_distance_along_the_view():
    positions = np.array([[-5, -5, -2], [5, -5, -2], [5, 5, -2], [-5, 5, -2]], dtype=float)
    scene = facet.Scene()
    scene.add(facet.Mesh.from_arrays(positions, [[0, 1, 2], [0, 2, 3]]))
    scene.add(facet.OrthographicCamera(xmag=2, ymag=1.5, znear=0.5, zfar=20), pose=look_at((0, 0, 4)))
    depth = facet.OffscreenRenderer(32, 24, threads=1, samples=1).render(scene, facet.RenderFlags.DEPTH_ONLY)
    np.testing.assert_allclose(depth, 6.0, rtol=1e-5)


@pytest.mark.parametrize("point", [(0.3, -0.2, -3.0), (-0.8, 0.5, -4.0), (0.05, 0.6, -2.5)])
def test_intrinsics_put_a_point_where_the_pinhole_model_does(point):
    width, height = 200, 150
    fx, fy, cx, cy = 180.0, 170.0, 97.3, 81.6
    camera = facet.IntrinsicsCamera(fx, fy, cx, cy, znear=0.1, zfar=10.0)
    # A square around the point, facing the camera (which sits at the origin, looking down -z).
    x, y, z = point
    s = 0.03 * -z  # about 5 pixels either side
    positions = np.array([[x - s, y - s, z], [x + s, y - s, z], [x + s, y + s, z], [x - s, y + s, z]])
    scene = facet.Scene()
    scene.add(facet.Mesh.from_arrays(positions, [[0, 1, 2], [0, 2, 3]]))
    scene.add(camera, pose=np.eye(4))
    renderer = facet.OffscreenRenderer(width, height, threads=1, samples=1)
    mask = renderer.render_buffers(scene, ["mask"])["mask"] == 255
    # OpenCV: x right, y down, z forward. The square projects to a rectangle centred on (u, v), and a pixel is
    # covered exactly when its centre (u, v integers) lies inside: a half-pixel slip would move a whole column.
    u, v = fx * x / -z + cx, fy * -y / -z + cy
    half_u, half_v = fx * s / -z, fy * s / -z
    rows, cols = np.mgrid[0:height, 0:width]
    du, dv = np.abs(cols - u), np.abs(rows - v)
    predicted = (du < half_u) & (dv < half_v)
    on_edge = (np.abs(du - half_u) < 1e-3) | (np.abs(dv - half_v) < 1e-3)
    assert predicted.sum() > 50
    np.testing.assert_array_equal(mask[~on_edge], predicted[~on_edge])
    k = np.array(renderer.camera_json(scene)["K"])
    np.testing.assert_allclose(k, [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], rtol=1e-5, atol=1e-3)


def test_rgba_alpha_is_zero_only_where_the_background_shows(sphere):
    scene = sphere_scene(sphere, facet.PerspectiveCamera(yfov=0.8), look_at((0, 0, 4)), bg_color=(0.2, 0.3, 0.4, 0.0))
    color, depth = facet.OffscreenRenderer(64, 48, threads=1, samples=1).render(scene, facet.RenderFlags.RGBA)
    assert color.shape == (48, 64, 4)
    np.testing.assert_array_equal(color[..., 3] == 255, depth > 0)
    np.testing.assert_array_equal(color[..., 3] == 0, depth == 0)
    opaque = facet.OffscreenRenderer(64, 48, threads=1).render(
        sphere_scene(sphere, facet.PerspectiveCamera(yfov=0.8), look_at((0, 0, 4))))[0]
    assert opaque.shape == (48, 64, 3)


@pytest.mark.parametrize("samples", [2, 4, 8])
def test_multisampling_blends_only_the_silhouette(sphere, samples):
    """Anti-aliased, alpha is each pixel's covered fraction; depth is taken at the pixel's centre, so it is set
    wherever every sample is covered (the centre lies among them), unset wherever none is, and either way on the
    silhouette."""
    scene = sphere_scene(sphere, facet.PerspectiveCamera(yfov=0.8), look_at((0, 0, 4)), bg_color=(0.2, 0.3, 0.4, 0.0))
    color, depth = facet.OffscreenRenderer(64, 48, threads=2, samples=samples).render(scene, facet.RenderFlags.RGBA)
    alpha = color[..., 3].astype(int)
    edge = (alpha > 0) & (alpha < 255)
    assert 20 < edge.sum() < 400
    assert np.all(depth[alpha == 255] > 0) and np.all(depth[alpha == 0] == 0)
    # Partly covered pixels take multiples of 255 / samples, rounded.
    allowed = {round(255 * k / samples) for k in range(1, samples)}
    assert set(np.unique(alpha[edge])) <= allowed


def test_buffers_agree_on_every_pixel(sphere):
    positions, faces, normals = sphere
    scene = facet.Scene(bg_color=(0.0, 0.0, 0.0, 1.0))
    mesh = facet.Mesh.from_arrays(positions, faces, normals=normals)
    scene.add(mesh, pose=np.eye(4))
    moved = np.eye(4)
    moved[:3, 3] = (1.5, 0.3, -1.0)
    node = scene.add(mesh, pose=moved)
    scene.add(facet.PerspectiveCamera(yfov=0.9), pose=look_at((0.5, 1.0, 5.0)))
    out = facet.OffscreenRenderer(96, 72, threads=1).render_buffers(scene, facet.BUFFERS)
    drawn = out["mask"] == 255
    assert 0.1 < drawn.mean() < 0.9
    np.testing.assert_array_equal(drawn, out["depth"] > 0)
    np.testing.assert_array_equal(drawn, out["ids"][..., 0] != 0xFFFFFFFF)
    np.testing.assert_array_equal(drawn, np.linalg.norm(out["normal"], axis=-1) > 0.5)
    assert set(np.unique(out["ids"][..., 0][drawn])) == {0, node.id}
    assert np.all(out["ids"][..., 1][drawn] < len(faces))


def test_scene_nodes_move_and_go(sphere):
    positions, faces, normals = sphere
    scene = facet.Scene()
    node = scene.add(facet.Mesh.from_arrays(positions, faces), pose=np.eye(4))
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 5)))
    renderer = facet.OffscreenRenderer(48, 36, threads=1)
    before = renderer.render(scene, facet.RenderFlags.DEPTH_ONLY)
    moved = np.eye(4)
    moved[0, 3] = 1.0
    scene.set_pose(node, moved)
    after = renderer.render(scene, facet.RenderFlags.DEPTH_ONLY)
    assert (before > 0).sum() == pytest.approx((after > 0).sum(), rel=0.1)
    assert not np.array_equal(before > 0, after > 0)
    scene.remove_node(node)
    assert not renderer.render(scene, facet.RenderFlags.DEPTH_ONLY).any()
    assert scene.mesh_nodes == set()


def test_flags_change_what_is_drawn(sphere):
    scene = sphere_scene(sphere, facet.PerspectiveCamera(yfov=0.8), look_at((0, 0, 4)))
    renderer = facet.OffscreenRenderer(64, 48, threads=1)
    color, depth = renderer.render(scene)
    wire, _ = renderer.render(scene, facet.RenderFlags.ALL_WIREFRAME)
    flat, _ = renderer.render(scene, facet.RenderFlags.FLAT)
    assert not np.array_equal(color, wire) and not np.array_equal(color, flat)
    node = next(iter(scene.mesh_nodes))
    seg, seg_depth = renderer.render(scene, facet.RenderFlags.SEG, {node: (10, 200, 30)})
    # pyrender's segmentation: the mapped node flat in its colour on black, at the depth it is drawn at.
    assert seg.shape == (48, 64, 3) and np.array_equal(seg_depth, depth)
    assert set(map(tuple, seg.reshape(-1, 3))) == {(0, 0, 0), (10, 200, 30)}
    np.testing.assert_array_equal(np.all(seg == (10, 200, 30), axis=-1), depth > 0)
    unmapped, unmapped_depth = renderer.render(scene, facet.RenderFlags.SEG)
    assert not unmapped.any() and not unmapped_depth.any()  # nodes outside the map are left out
    with pytest.raises(ValueError, match="flags"):
        renderer.render(scene, 1 << 20)


def test_from_file_scenes_keep_the_files_nodes():
    scene = facet.Scene.from_file(f"{MODELS}/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb")
    assert len(scene.mesh_nodes) > 10
    assert len({id(n.mesh) for n in scene.mesh_nodes}) < len(scene.mesh_nodes)  # meshes shared between nodes
    box = scene.bounds
    center, size = box.mean(axis=0), np.linalg.norm(box[1] - box[0])
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at(center + (0, 0.3 * size, 1.2 * size), center))
    out = facet.OffscreenRenderer(96, 72, threads=1).render_buffers(scene, ["ids", "mask"])
    seen = set(np.unique(out["ids"][..., 0][out["mask"] == 255]))
    assert seen and seen <= {n.id for n in scene.mesh_nodes}
    mesh = facet.Mesh.from_file(f"{MODELS}/PLY/Wuson.ply")
    assert mesh.triangle_count > 1000


@pytest.mark.parametrize("model", ["glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", "PLY/cube.ply",
                                   "STL/Spider_binary.stl", "OBJ/WusonOBJ.obj"])
def test_render_one_liner(model):
    out = facet.render(f"{MODELS}/{model}", width=80, height=60, buffers=["color", "depth", "ids", "mask"])
    assert out["color"].shape == (60, 80, 3)
    drawn = out["mask"] == 255
    assert drawn.any()
    np.testing.assert_array_equal(drawn, out["depth"] > 0)
    assert out["camera"]["width"] == 80 and len(out["camera"]["K"]) == 3


def test_the_one_liner_matches_the_cli(tmp_path):
    """facet.render draws what `facet render` draws: the same RenderJob."""
    import os
    import pathlib
    import subprocess
    import zlib
    # The CLI of the build tree the package was imported from (build/python/facet -> build/tools/facet).
    cli = os.environ.get("FACET_CLI", str(pathlib.Path(facet.__file__).parents[2] / "tools" / "facet"))
    png = tmp_path / "wuson.png"
    subprocess.run([cli, "render", f"{MODELS}/OBJ/WusonOBJ.obj", "--output", str(png), "--resolution", "80,60"],
                   check=True)
    data = png.read_bytes()
    idat = b""
    pos = 8
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        if data[pos + 4:pos + 8] == b"IDAT":
            idat += data[pos + 8:pos + 8 + length]
        pos += 12 + length
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(60, 1 + 80 * 3)
    rows = raw[:, 1:].astype(np.int32)
    for y in range(60):  # undo the PNG filters (facet writes Up or None)
        if raw[y, 0] == 2 and y > 0:
            rows[y] = (rows[y] + rows[y - 1]) % 256
    image = rows.reshape(60, 80, 3).astype(np.uint8)
    out = facet.render(f"{MODELS}/OBJ/WusonOBJ.obj", width=80, height=60)
    np.testing.assert_array_equal(out["color"], image)


def test_a_point_cloud_covers_a_square_of_point_size_around_each_projected_point():
    width, height = 120, 90
    fx, fy, cx, cy = 100.0, 100.0, 60.0, 45.0
    camera = facet.IntrinsicsCamera(fx, fy, cx, cy, znear=0.1, zfar=10.0)
    # Points in front of the camera (OpenGL axes: -z forward), projected at non-integer pixel positions.
    points = np.array([[-0.503, 0.2, -2.0], [0.307, -0.111, -2.0], [0.0, 0.0, -3.0]])
    colors = np.array([[255, 0, 0], [0, 255, 0], [0, 0, 255]], dtype=np.uint8)
    cloud = facet.Mesh.from_points(points, colors=colors)
    assert cloud.point_count == 3 and cloud.triangle_count == 0
    scene = facet.Scene(bg_color=[0, 0, 0])
    scene.add(cloud)
    scene.add(camera, pose=np.eye(4))
    for size in (1.0, 3.0, 5.5):
        renderer = facet.OffscreenRenderer(width, height, point_size=size, threads=1, samples=1)
        out = renderer.render_buffers(scene, ["color", "mask", "depth"], facet.RenderFlags.FLAT)
        rows, cols = np.mgrid[0:height, 0:width]
        predicted = np.zeros((height, width), dtype=bool)
        for (x, y, z), color in zip(points, colors):
            u, v = fx * x / -z + cx, fy * -y / -z + cy  # OpenCV: pixel (0, 0)'s centre at u = v = 0
            square = (np.abs(cols - u) < size / 2) & (np.abs(rows - v) < size / 2)
            predicted |= square
            # Drawn flat (unlit) in its own colour, at its distance.
            np.testing.assert_array_equal(out["color"][square], np.broadcast_to(color, (square.sum(), 3)))
            np.testing.assert_allclose(out["depth"][square], -z, rtol=1e-5)
        np.testing.assert_array_equal(out["mask"] == 255, predicted)


def test_bad_point_clouds_and_point_sizes_raise_value_error():
    with pytest.raises(ValueError, match="positions"):
        facet.Mesh.from_points(np.array([[0.0, np.nan, 0.0]]))
    with pytest.raises(ValueError, match="color"):
        facet.Mesh.from_points(np.zeros((3, 3)), colors=np.zeros((2, 3)))
    for size in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="point_size"):
            facet.OffscreenRenderer(16, 12, point_size=size, threads=1)


def test_a_gaussian_splat_file_shows_its_gaussian_where_the_camera_projects_it(tmp_path):
    # One Gaussian in the 3D Gaussian Splatting paper's PLY layout: colour (1, 0.5, 0), opacity sigmoid(2).
    names = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
             "rot_0", "rot_1", "rot_2", "rot_3"]
    dc = [(c - 0.5) / 0.28209479177387814 for c in (1.0, 0.5, 0.0)]
    values = np.array([0.0, 0.0, -2.0, *dc, 2.0, *[np.log(0.05)] * 3, 1.0, 0.0, 0.0, 0.0], dtype="<f4")
    path = tmp_path / "one.ply"
    header = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
    path.write_bytes((header + "".join(f"property float {n}\n" for n in names) + "end_header\n").encode() +
                     values.tobytes())
    scene = facet.Scene.from_file(str(path), bg_color=[0, 0, 0])
    scene.add(facet.IntrinsicsCamera(100.0, 100.0, 60.0, 45.0, znear=0.1, zfar=10.0), pose=np.eye(4))
    color, _ = facet.OffscreenRenderer(120, 90, threads=1, samples=1).render(scene)
    # On the axis, so at pixel (60, 45)'s centre (OpenCV's convention, the paper's too): alpha is the opacity.
    alpha = 1.0 / (1.0 + np.exp(-2.0))
    np.testing.assert_allclose(color[45, 60], np.array([1.0, 0.5, 0.0]) * alpha * 255.0, atol=1.0)
    # 2.5 pixels of standard deviation (0.05 at depth 2, 100 px a unit at depth 1): faded 10 pixels out.
    assert color[45, 70].max() < color[45, 60].max() / 10


def test_a_bare_cloud_is_drawn_with_eye_dome_lighting_unless_turned_off(tmp_path):
    # Two squares of points, one in front of the other, with neither normals nor colours.
    grid = np.stack(np.meshgrid(np.linspace(-1, 1, 90), np.linspace(-1, 1, 90)), -1).reshape(-1, 2)
    near = np.column_stack([grid * 0.4, np.full(len(grid), 0.5)])
    far = np.column_stack([grid, np.zeros(len(grid))])
    path = tmp_path / "bare.xyz"
    np.savetxt(path, np.vstack([far, near]))
    shade = {s: facet.render(path, 64, 48, buffers=("color",), threads=1, samples=1, eye_dome_lighting=s)["color"]
             for s in (None, 0, 1)}
    np.testing.assert_array_equal(shade[None], shade[1])  # on, at strength 1, by default
    darker = shade[0].astype(int) - shade[1].astype(int)
    assert darker.min() >= 0 and (darker.max(axis=2) > 100).sum() > 20  # the far square's ring around the near one
    with pytest.raises(ValueError, match="eye-dome lighting"):
        facet.render(path, 64, 48, eye_dome_lighting=-1)


def test_a_cloud_coloured_by_height_runs_from_blue_below_to_red_above(tmp_path):
    heights = np.linspace(-1, 1, 400)
    path = tmp_path / "column.xyz"
    np.savetxt(path, np.column_stack([np.zeros_like(heights), heights, np.zeros_like(heights)]))
    color = facet.render(path, 48, 64, buffers=("color",), threads=1, samples=1, shading="unlit",
                         eye_dome_lighting=0, color_map="height")["color"].astype(int)
    off_background = np.abs(color - color[0, 0]).sum(axis=2)
    drawn = np.flatnonzero((off_background > 30).any(axis=1))  # the rows the column covers

    def column_pixel(row):
        return color[row, off_background[row].argmax()]

    top, bottom = column_pixel(drawn[0]), column_pixel(drawn[-1])
    assert top[0] > 200 and top[2] < 60     # red at the top of the image
    assert bottom[2] > 200 and bottom[0] < 60  # blue at the bottom
    with pytest.raises(ValueError, match="color_map"):
        facet.render(path, 48, 64, color_map="rainbow")


def test_a_scan_coloured_by_intensity_runs_from_black_to_white(tmp_path):
    heights = np.linspace(-1, 1, 400)
    path = tmp_path / "scan.xyz"
    np.savetxt(path, np.column_stack([np.zeros_like(heights), heights, np.zeros_like(heights), 500 + 100 * heights]))
    color = facet.render(path, 48, 64, buffers=("color",), threads=1, samples=1, background=(1, 0, 0, 1),
                         color_map="intensity")["color"].astype(int)
    drawn = color[(color != (255, 0, 0)).any(axis=2)]
    assert len(drawn) > 50 and (drawn[:, 0] == drawn[:, 1]).all() and (drawn[:, 1] == drawn[:, 2]).all()
    assert drawn[:, 0].min() < 40 and drawn[:, 0].max() > 215  # the weakest black, the strongest white
    with pytest.raises(Exception, match="no intensities"):
        facet.render(_write_cloud(tmp_path), 48, 64, color_map="intensity")


def _write_cloud(tmp_path):
    path = tmp_path / "plain.xyz"
    np.savetxt(path, np.eye(3))
    return path


def test_a_gaussian_shows_in_the_depth_and_mask_where_it_covers_half_a_pixel(tmp_path):
    names = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
             "rot_0", "rot_1", "rot_2", "rot_3"]
    values = np.array([0.0, 0.0, -2.0, 1.0, 1.0, 1.0, 2.0, *[np.log(0.05)] * 3, 1.0, 0.0, 0.0, 0.0], dtype="<f4")
    path = tmp_path / "one.ply"
    header = "ply\nformat binary_little_endian 1.0\nelement vertex 1\n"
    path.write_bytes((header + "".join(f"property float {n}\n" for n in names) + "end_header\n").encode() +
                     values.tobytes())
    for samples in (1, 4):
        scene = facet.Scene.from_file(str(path), bg_color=[0, 0, 0])
        scene.add(facet.IntrinsicsCamera(100.0, 100.0, 60.0, 45.0, znear=0.1, zfar=10.0), pose=np.eye(4))
        out = facet.OffscreenRenderer(120, 90, threads=1, samples=samples).render_buffers(scene, ["depth", "mask"])
        assert out["depth"][45, 60] == pytest.approx(2.0, abs=1e-4)
        assert out["mask"][45, 60] == 255 and out["mask"][45, 70] == 0 and out["depth"][45, 70] == 0
        # Alpha sigmoid(2) exp(-r^2 / 2 sigma^2) >= 0.5 within r = 2.7 pixels (sigma 2.5): about 22 pixels.
        assert 14 <= (out["mask"] == 255).sum() <= 30
        assert ((out["mask"] == 255) == (out["depth"] > 0)).all()
