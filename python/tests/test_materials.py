"""test_materials.py - MetallicRoughnessMaterial: factors as pyrender means them, culling, alpha, textures, errors."""
import base64
import json
import types

import numpy as np
import pytest

import facet
from conftest import look_at, uv_sphere

SQUARE = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)
SQUARE_FACES = np.array([[0, 1, 2], [0, 2, 3]])
SQUARE_NORMALS = np.tile([0.0, 0.0, 1.0], (4, 1))
SQUARE_UVS = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)


def square_scene(mesh, eye=(0, 0, 3), ambient=(0.0, 0.0, 0.0), light=None, bg_color=(0.0, 0.0, 0.0, 1.0)):
    scene = facet.Scene(ambient_light=ambient, bg_color=bg_color)
    scene.add(mesh)
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at(eye))
    if light is not None:
        scene.add(light, pose=np.eye(4))  # a directional light along -z: square on
    return scene


def draw(scene, flags=facet.RenderFlags.NONE, size=(32, 24)):
    return facet.OffscreenRenderer(*size, threads=1, samples=1).render(scene, flags)


def test_a_linear_base_colour_is_displayed_srgb_encoded():
    """pyrender's factors are linear: 0.604 is sRGB 0.800 (204), which the flat shading shows as it is under a
    perpendicular light of intensity 1 and no ambient light."""
    material = facet.MetallicRoughnessMaterial(baseColorFactor=[0.604, 0.604, 0.604, 1.0], metallicFactor=0.0,
                                               roughnessFactor=1.0)
    mesh = facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, material=material)
    color, depth = draw(square_scene(mesh, light=facet.DirectionalLight(intensity=1.0)), facet.RenderFlags.FLAT)
    assert (depth > 0).sum() > 100
    assert np.all(np.abs(color[depth > 0].astype(int) - 204) <= 1)


def gltf_square(path, material):
    """A glTF file of the square with one material, its buffer inline."""
    positions = SQUARE.astype(np.float32)
    normals = SQUARE_NORMALS.astype(np.float32)
    indices = SQUARE_FACES.astype(np.uint16).reshape(-1)
    blob = positions.tobytes() + normals.tobytes() + indices.tobytes()
    views = [(0, 48), (48, 48), (96, 12)]
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [material],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": n} for o, n in views],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0],
             "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    path.write_text(json.dumps(gltf))
    return path


@pytest.mark.parametrize("base, metallic, roughness, emissive", [
    ([0.604, 0.2, 0.05, 1.0], 0.0, 1.0, [0.0, 0.0, 0.0]),
    ([0.9, 0.7, 0.3, 1.0], 1.0, 0.3, [0.0, 0.0, 0.0]),
    ([0.1, 0.3, 0.8, 1.0], 0.4, 0.6, [0.3, 0.1, 0.0]),
])
def test_a_material_draws_as_the_same_material_read_from_gltf(tmp_path, base, metallic, roughness, emissive):
    """The physically based look of a MetallicRoughnessMaterial is that of the glTF material with the same
    factors: the base colour converted alike, the emission passed through linear, the same lights."""
    gltf = {"pbrMetallicRoughness": {"baseColorFactor": base, "metallicFactor": metallic,
                                     "roughnessFactor": roughness}, "emissiveFactor": emissive}
    from_file = facet.Scene.from_file(gltf_square(tmp_path / "square.gltf", gltf), ambient_light=(0.1, 0.1, 0.1))
    material = facet.MetallicRoughnessMaterial(baseColorFactor=base, metallicFactor=metallic,
                                               roughnessFactor=roughness, emissiveFactor=emissive)
    made = facet.Scene(ambient_light=(0.1, 0.1, 0.1))
    made.add(facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, material=material))
    images = []
    for scene in (from_file, made):
        scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0.4, 0.3, 3.0)))
        scene.add(facet.DirectionalLight(intensity=2.0), pose=look_at((1, 2, 3)))
        point = np.eye(4)
        point[:3, 3] = (-0.5, 0.5, 1.0)
        scene.add(facet.PointLight(color=(1.0, 0.8, 0.6), intensity=1.5), pose=point)
        images.append(draw(scene, size=(48, 36))[0])
    assert (images[1].astype(int).sum(axis=-1) > 30).sum() > 500
    np.testing.assert_array_equal(images[0], images[1])


def test_a_metal_and_a_rough_dielectric_look_different():
    positions, faces, normals = uv_sphere(rings=48, segments=96)
    images = {}
    for name, metallic, roughness in (("metal", 1.0, 0.2), ("dielectric", 0.0, 1.0)):
        material = facet.MetallicRoughnessMaterial(baseColorFactor=[0.9, 0.6, 0.3, 1.0], metallicFactor=metallic,
                                                   roughnessFactor=roughness)
        scene = facet.Scene(ambient_light=(0.1, 0.1, 0.1))
        scene.add(facet.Mesh.from_arrays(positions, faces, normals=normals, material=material))
        scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 4)))
        scene.add(facet.DirectionalLight(intensity=3.0), pose=look_at((1, 2, 3)))
        color, depth = draw(scene, size=(64, 48))
        images[name] = color[depth > 0].astype(int).sum(axis=-1) / 3
    metal, dielectric = images["metal"], images["dielectric"]
    assert metal.size == dielectric.size > 500
    # Without an environment a metal shows the light's small, bright highlight and, elsewhere, the ambient light
    # reflected in its colour (about base x ambient: sRGB 85, 68, 48). The rough dielectric scatters the light over
    # its whole lit side.
    assert 55 < np.median(metal) < 80 < 0.5 * np.median(dielectric)
    assert metal.max() > 200
    assert (metal > 150).mean() < 0.1 < (dielectric > 150).mean()


def test_single_sided_materials_cull_their_back_faces():
    """Seen from behind, a square is drawn only when its material is double-sided or culling is skipped."""
    def drawn(material, flags=facet.RenderFlags.NONE):
        mesh = facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, material=material)
        return (draw(square_scene(mesh, eye=(0, 0, -3)), flags)[1] > 0).sum()

    assert drawn(None) == 0
    assert drawn(facet.MetallicRoughnessMaterial()) == 0
    assert drawn(facet.MetallicRoughnessMaterial(doubleSided=True)) > 100
    assert drawn(None, facet.RenderFlags.SKIP_CULL_FACES) > 100


def test_alpha_modes():
    def color_of(**kwargs):
        material = facet.MetallicRoughnessMaterial(baseColorFactor=[1.0, 1.0, 1.0, 0.4], metallicFactor=0.0,
                                                   **kwargs)
        mesh = facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, material=material)
        color, depth = draw(square_scene(mesh, ambient=(1.0, 1.0, 1.0), bg_color=(0.0, 0.0, 1.0, 1.0)))
        return color[12, 16].astype(int), (depth > 0).sum()

    opaque, _ = color_of()
    assert opaque[0] > 150 and opaque[2] == opaque[0]  # alpha ignored: white, no blue behind
    _, masked = color_of(alphaMode="MASK", alphaCutoff=0.5)
    assert masked == 0
    _, kept = color_of(alphaMode="MASK", alphaCutoff=0.3)
    assert kept > 100
    blended, _ = color_of(alphaMode="BLEND")
    assert 30 < blended[0] < opaque[0] - 30 and blended[2] > blended[0] + 30  # the blue background shows through


def test_a_base_colour_texture_is_drawn_with_the_uvs():
    texture = np.zeros((1, 2, 3), dtype=np.uint8)
    texture[0, 0] = (255, 0, 0)  # left: red
    texture[0, 1] = (0, 255, 0)  # right: green
    material = facet.MetallicRoughnessMaterial(baseColorTexture=texture, metallicFactor=0.0)
    mesh = facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, uvs=SQUARE_UVS, material=material)
    color, _ = draw(square_scene(mesh, ambient=(1.0, 1.0, 1.0)), size=(64, 48))
    left, right = color[24, 24].astype(int), color[24, 40].astype(int)
    assert left[0] > left[1] + 80 and right[1] > right[0] + 80


def test_from_trimesh_takes_a_material_in_place_of_vertex_colours():
    positions, faces, normals = uv_sphere(rings=16, segments=32)
    colors = np.tile([0, 0, 255, 255], (len(positions), 1)).astype(np.uint8)
    tm = types.SimpleNamespace(vertices=positions, faces=faces, vertex_normals=normals,
                               visual=types.SimpleNamespace(kind="vertex", vertex_colors=colors))
    material = facet.MetallicRoughnessMaterial(baseColorFactor=[1.0, 0.0, 0.0, 1.0], metallicFactor=0.0)

    def center(mesh):
        scene = facet.Scene(ambient_light=(1.0, 1.0, 1.0))
        scene.add(mesh)
        scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 4)))
        return draw(scene)[0][12, 16].astype(int)

    assert center(facet.Mesh.from_trimesh(tm))[2] > 100  # its vertex colours: blue
    red = center(facet.Mesh.from_trimesh(tm, material=material))
    assert red[0] > red[2] + 100
    np.testing.assert_array_equal(red, center(facet.Mesh.from_arrays(positions, faces, normals=normals, material=material)))


def test_a_wireframe_material_draws_its_mesh_as_lines_and_the_flags_override_it():
    """One wireframe mesh beside a solid one: the flags turn either or both into lines as pyrender's do."""
    def covered(flags, wireframe):
        scene = square_scene(facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS,
                                                    material=facet.MetallicRoughnessMaterial(wireframe=wireframe)))
        return (draw(scene, flags=flags)[1] > 0).sum()

    solid, lines = covered(facet.RenderFlags.NONE, False), covered(facet.RenderFlags.NONE, True)
    assert 0 < lines < solid / 2
    assert covered(facet.RenderFlags.FLIP_WIREFRAME, True) == solid
    assert covered(facet.RenderFlags.FLIP_WIREFRAME, False) == lines
    assert covered(facet.RenderFlags.ALL_WIREFRAME, False) == lines
    assert covered(facet.RenderFlags.ALL_SOLID, True) == solid


@pytest.mark.parametrize("make, message", [
    (lambda: facet.MetallicRoughnessMaterial(metallicFactor=1.5), "metallicFactor"),
    (lambda: facet.MetallicRoughnessMaterial(roughnessFactor=-0.1), "roughnessFactor"),
    (lambda: facet.MetallicRoughnessMaterial(roughnessFactor=float("nan")), "roughnessFactor"),
    (lambda: facet.MetallicRoughnessMaterial(alphaMode="CLEAR"), "alphaMode"),
    (lambda: facet.MetallicRoughnessMaterial(alphaCutoff=2.0), "alphaCutoff"),
    (lambda: facet.MetallicRoughnessMaterial(baseColorFactor=[1.2, 0.0, 0.0]), "baseColorFactor"),
    (lambda: facet.MetallicRoughnessMaterial(baseColorFactor=[0.5] * 5), "baseColorFactor"),
    (lambda: facet.MetallicRoughnessMaterial(baseColorFactor=[0.5, float("nan"), 0.5]), "baseColorFactor"),
    (lambda: facet.MetallicRoughnessMaterial(emissiveFactor=[-1.0, 0.0, 0.0]), "emissiveFactor"),
    (lambda: facet.MetallicRoughnessMaterial(baseColorTexture="red.png"), "baseColorTexture"),
    (lambda: facet.MetallicRoughnessMaterial(baseColorTexture=np.zeros((2, 2, 3), dtype=np.int32) + 300),
     "baseColorTexture"),
    (lambda: facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, material="red"), "material"),
    (lambda: facet.Mesh.from_arrays(SQUARE, SQUARE_FACES,
                        material=facet.MetallicRoughnessMaterial(baseColorTexture=np.zeros((2, 2, 3)))), "uvs"),
    (lambda: facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, uvs=SQUARE_UVS,
                        material=facet.MetallicRoughnessMaterial(emissiveTexture=np.full((2, 2, 3), 2.0))),
     "emissiveTexture"),
])
def test_bad_material_values_raise_value_error(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_non_boolean_flags_raise_type_error():
    with pytest.raises(TypeError, match="doubleSided"):
        facet.MetallicRoughnessMaterial(doubleSided="yes")


def test_pyrenders_default_material_a_white_metal_is_lit():
    mesh = facet.Mesh.from_arrays(SQUARE, SQUARE_FACES, normals=SQUARE_NORMALS, material=facet.MetallicRoughnessMaterial())
    color, depth = draw(square_scene(mesh, light=facet.DirectionalLight(intensity=3.0)))
    assert np.median(color[depth > 0]) > 50


def test_a_primitives_vertex_colours_tint_the_lit_colour_as_pyrenders_do():
    """pyrender multiplies the lit colour, highlight included, by COLOR_0 (a linear value); Mesh.from_arrays'
    colours are facet's: displayed values multiplying the base colour, under a white highlight."""
    positions, faces, normals = uv_sphere(rings=32, segments=64)
    red = np.tile([1.0, 0.0, 0.0, 1.0], (len(positions), 1))
    material = facet.MetallicRoughnessMaterial(metallicFactor=0.2, roughnessFactor=0.3)

    def brightest(mesh):
        scene = facet.Scene(ambient_light=(0.0, 0.0, 0.0), bg_color=(0.0, 0.0, 0.0, 1.0))
        scene.add(mesh)
        scene.add(facet.PerspectiveCamera(yfov=0.8), pose=look_at((0, 0, 4)))
        scene.add(facet.DirectionalLight(intensity=4.0), pose=look_at((0, 0, 4)))
        color = draw(scene, size=(64, 48))[0].astype(int)
        return color.reshape(-1, 3)[color.sum(axis=-1).argmax()]

    primitive = facet.Primitive(positions=positions, normals=normals, indices=faces, color_0=red, material=material)
    tinted = brightest(facet.Mesh([primitive]))
    assert tinted[0] > 200 and tinted[1] < 10 and tinted[2] < 10
    white_highlight = brightest(facet.Mesh.from_arrays(positions, faces, normals=normals, colors=red,
                                                       material=material))
    assert white_highlight[0] > 200 and white_highlight[1] > 60


def test_a_point_cloud_without_normals_is_lit_as_facing_the_camera():
    """pyrender lights points without normals as if each faced the camera: a light from the camera lights them
    more than one from the side, and FLAT draws them in their colours."""
    def centre(light, flags=facet.RenderFlags.NONE):
        scene = facet.Scene(bg_color=(0.0, 0.0, 0.0, 1.0))
        scene.add(facet.Mesh.from_points(np.zeros((1, 3)), colors=[[0.2, 0.6, 1.0]]))
        scene.add(facet.PerspectiveCamera(yfov=0.5), pose=look_at((0, 0, 3)))
        scene.add(facet.DirectionalLight(intensity=2.0), pose=look_at(light))
        renderer = facet.OffscreenRenderer(32, 24, point_size=5, threads=1, samples=1)
        return renderer.render(scene, flags)[0][12, 16].astype(int)

    front, side = centre((0, 0, 3)), centre((3, 0, 0.3))
    assert front[2] > side[2] + 60
    np.testing.assert_array_equal(centre((3, 0, 0.3), facet.RenderFlags.FLAT), [51, 153, 255])
