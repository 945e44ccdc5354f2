"""Tests of the trimesh stand-in's readers (tests/support): OBJ with MTL and textures, glTF 2.0 as GLB or JSON."""
import base64
import io
import json
import struct
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

# The stand-in lives beside the tests rather than on the global path; facet itself never imports trimesh.
sys.path.insert(0, str(Path(__file__).resolve().parent / "support"))
import trimesh  # noqa: E402
from trimesh import transformations as tf  # noqa: E402


# --- OBJ --------------------------------------------------------------------------------------------------------

OBJ_TEXT = """# a quad and a triangle sharing an edge, the triangle with negative indices
mtllib tiny.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 2 0.5 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vt 0.5 0.5
vn 0 0 2
usemtl shiny
f 1/1/1 2/2/1 3/3/1 4/4/1
f -4/-1/-1 -1/-2/-1 -3/-3/-1
"""

MTL_TEXT = """newmtl shiny
Kd 0.5 0.25 1.0
Ns 10
illum 2
map_Kd -s 1 1 1 tex.png
"""


@pytest.fixture
def obj_path(tmp_path):
    (tmp_path / "tiny.obj").write_text(OBJ_TEXT)
    (tmp_path / "tiny.mtl").write_text(MTL_TEXT)
    Image.fromarray(np.array([[[255, 0, 0], [0, 255, 0]], [[0, 0, 255], [255, 255, 255]]], np.uint8)).save(
        tmp_path / "tex.png")
    return tmp_path / "tiny.obj"


def test_obj_splits_vertices_per_uv_and_fans_polygons(obj_path):
    mesh = trimesh.load(str(obj_path))
    assert isinstance(mesh, trimesh.Trimesh)
    # The quad becomes two triangles around its first corner; vertex 2 is used with two uvs, so it is split.
    assert mesh.faces.shape == (3, 3)
    assert mesh.vertices.shape == (6, 3)
    corners = mesh.vertices[mesh.faces]
    assert np.allclose(corners[0], [[0, 0, 0], [1, 0, 0], [1, 1, 0]])
    assert np.allclose(corners[1], [[0, 0, 0], [1, 1, 0], [0, 1, 0]])
    assert np.allclose(corners[2], [[1, 0, 0], [2, 0.5, 0], [1, 1, 0]])
    uv = mesh.visual.uv[mesh.faces]
    assert np.allclose(uv[0], [[0, 0], [1, 0], [1, 1]])
    assert np.allclose(uv[2], [[0.5, 0.5], [0, 1], [1, 1]])
    assert np.allclose(mesh.vertex_normals, [0, 0, 1])


def test_obj_material_image_and_raw_keys(obj_path):
    mesh = trimesh.load(obj_path)
    assert isinstance(mesh.visual, trimesh.visual.TextureVisuals)
    material = mesh.visual.material
    assert isinstance(material, trimesh.visual.texture.SimpleMaterial)
    assert material.image.size == (2, 2)
    assert np.array_equal(material.diffuse, [128, 64, 255, 255])
    assert material.kwargs["Ns"] == 10.0 and material.glossiness == 10.0
    assert material.kwargs["illum"] == 2.0
    colors = mesh.visual.to_color().vertex_colors
    # uv (0, 0) is the image's bottom-left texel: blue.
    assert np.array_equal(colors[mesh.faces[0, 0], :3], [0, 0, 255])


def test_obj_without_materials_keeps_vertices(tmp_path):
    path = tmp_path / "plain.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nf 1 2 3\n")
    mesh = trimesh.load(path)
    assert mesh.vertices.shape == (4, 3) and not mesh.visual.defined
    assert np.allclose(mesh.face_normals, [[0, 0, 1]])


def test_obj_several_materials_give_a_scene_and_mtl_colours_follow_the_spec(tmp_path):
    (tmp_path / "two.mtl").write_text("newmtl red\nKd 1 0 0\nKs 0\nnewmtl blue\nKd 0 0 1\n")
    (tmp_path / "two.obj").write_text("mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                      "usemtl red\nf 1 2 3\nusemtl blue\nf 2 4 3\n")
    scene = trimesh.load(tmp_path / "two.obj")
    assert isinstance(scene, trimesh.Scene) and list(scene.geometry) == ["red", "blue"]
    red = scene.geometry["red"].visual.material
    assert np.array_equal(red.diffuse, [255, 0, 0, 255]) and np.array_equal(red.specular, [0, 0, 0, 255])
    # Each material's mesh keeps only the vertices its faces use.
    assert scene.geometry["blue"].vertices.shape == (3, 3)
    assert np.allclose(scene.bounds, [[0, 0, 0], [1, 1, 0]])


def test_obj_in_utf16(tmp_path):
    path = tmp_path / "wide.obj"
    path.write_bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".encode("utf-16"))
    assert trimesh.load(path).faces.shape == (1, 3)


@pytest.mark.parametrize("text, problem", [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "vertex index 4"),
    ("v 0 0 zero\n", "needs numbers"),
    ("v 0 0 0\nv 1 0 0\nf 1 2\n", "at least 3"),
    ("# nothing here\n", "no vertices"),
])
def test_malformed_obj_names_file_and_problem(tmp_path, text, problem):
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(ValueError, match=problem) as caught:
        trimesh.load(path)
    assert "bad.obj" in str(caught.value)


def test_unknown_type_and_missing_file(tmp_path):
    (tmp_path / "x.stl").write_text("solid x\n")
    with pytest.raises(ValueError, match="x.stl"):
        trimesh.load(tmp_path / "x.stl")
    with pytest.raises(FileNotFoundError):
        trimesh.load(tmp_path / "nope.obj")


# --- glTF -------------------------------------------------------------------------------------------------------

def _png_bytes():
    image = np.zeros((4, 4, 3), np.uint8)
    image[:2] = [255, 0, 0]
    image[2:] = [0, 0, 255]
    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, "PNG")
    return buffer.getvalue()


def _tiny_gltf():
    """(document, binary): a textured triangle (interleaved POSITION+NORMAL, uint16 indices) placed by a child node
    (scale 2) of a parent node (turn about z and translation) that places a vertex-coloured triangle."""
    positions = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    normals = np.tile(np.array([0, 0, 1], np.float32), (3, 1))
    interleaved = np.hstack([positions, normals]).astype(np.float32).tobytes()
    uv = np.array([[0, 0], [1, 0], [0, 1]], np.float32).tobytes()
    indices = np.array([0, 1, 2], np.uint16).tobytes() + b"\0\0"
    colors = np.array([[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255]], np.uint8).tobytes()
    image = _png_bytes()
    blobs, views, binary = [interleaved, uv, indices, colors, image], [], b""
    for blob in blobs:
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(blob)})
        binary += blob + b"\0" * (-len(blob) % 4)
    views[0]["byteStride"] = 24
    document = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "parent", "mesh": 1, "children": [1], "translation": [1, 2, 3],
                   "rotation": [0, 0, np.sqrt(0.5), np.sqrt(0.5)]},
                  {"name": "child", "mesh": 0, "scale": [2, 2, 2]}],
        "meshes": [{"name": "textured", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                          "indices": 3, "material": 0}]},
                   {"name": "colored", "primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 4}}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"},
            {"bufferView": 3, "componentType": 5121, "normalized": True, "count": 3, "type": "VEC4"}],
        "bufferViews": views, "buffers": [{"byteLength": len(binary)}],
        "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "textures": [{"source": 0}],
        "materials": [{"name": "paint", "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.5, 0.25, 1.0], "baseColorTexture": {"index": 0},
            "metallicFactor": 0.3, "roughnessFactor": 0.6},
            "emissiveFactor": [0.1, 0.2, 0.3], "doubleSided": True, "alphaMode": "MASK", "alphaCutoff": 0.4}],
    }
    return document, binary


def _glb_raw(text, binary):
    text += b" " * (-len(text) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text
            + struct.pack("<II", len(binary), 0x004E4942) + binary)


def _glb(document, binary):
    return _glb_raw(json.dumps(document).encode(), binary)


PARENT = tf.translation_matrix([1, 2, 3]) @ tf.rotation_matrix(np.pi / 2, [0, 0, 1])


def _check_tiny_scene(scene):
    assert isinstance(scene, trimesh.Scene)
    assert list(scene.geometry) == ["textured", "colored"]
    assert scene.graph.nodes_geometry == ["parent", "child"]
    pose, name = scene.graph["child"]
    assert name == "textured" and pose.dtype == np.float64
    assert np.allclose(pose, PARENT @ np.diag([2.0, 2.0, 2.0, 1.0]))
    assert np.allclose(scene.graph["parent"][0], PARENT)
    textured = scene.geometry["textured"]
    assert np.allclose(textured.vertices, [[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    assert np.array_equal(textured.faces, [[0, 1, 2]])
    # glTF's v runs down the image; trimesh's runs up.
    assert np.allclose(textured.visual.uv, [[0, 1], [1, 1], [0, 0]])
    material = textured.visual.material
    assert isinstance(material, trimesh.visual.texture.PBRMaterial)
    assert np.array_equal(material.baseColorFactor, [255, 128, 64, 255])
    assert material.metallicFactor == pytest.approx(0.3) and material.roughnessFactor == pytest.approx(0.6)
    assert np.allclose(material.emissiveFactor, [0.1, 0.2, 0.3])
    assert material.doubleSided and material.alphaMode == "MASK" and material.alphaCutoff == pytest.approx(0.4)
    assert np.array_equal(np.asarray(material.baseColorTexture.convert("RGB"))[0, 0], [255, 0, 0])
    # Vertex 2 (glTF uv (0, 1), trimesh uv (0, 0)) sits on the image's bottom row, blue; vertex 0 on its top, red.
    sampled = textured.visual.to_color().vertex_colors
    assert np.array_equal(sampled[2, :3], [0, 0, 255]) and np.array_equal(sampled[0, :3], [255, 0, 0])
    colored = scene.geometry["colored"]
    assert colored.visual.kind == "vertex"
    assert np.array_equal(colored.visual.vertex_colors[:, :3], [[255, 0, 0], [0, 255, 0], [0, 0, 255]])
    dumped = scene.dump()
    assert len(dumped) == 2
    moved = PARENT @ np.diag([2.0, 2.0, 2.0, 1.0])
    assert np.allclose(dumped[1].vertices, tf.transform_points(textured.vertices, moved))
    assert np.allclose(dumped[1].vertex_normals, [0, 0, 1])
    assert np.allclose(textured.vertices, [[0, 0, 0], [1, 0, 0], [0, 1, 0]])
    assert np.allclose(scene.bounds, [[-1, 2, 3], [1, 4, 3]])


def test_glb_scene_geometry_graph_and_dump(tmp_path):
    path = tmp_path / "tiny.glb"
    path.write_bytes(_glb(*_tiny_gltf()))
    _check_tiny_scene(trimesh.load(path))
    _check_tiny_scene(trimesh.load(io.BytesIO(path.read_bytes()), file_type="glb"))


def test_gltf_json_with_data_uris(tmp_path):
    document, binary = _tiny_gltf()
    document["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
    path = tmp_path / "tiny.gltf"
    path.write_text(json.dumps(document))
    _check_tiny_scene(trimesh.load(path))


def test_gltf_without_indices_and_with_external_buffer(tmp_path):
    document, binary = _tiny_gltf()
    document["buffers"][0]["uri"] = "tiny.bin"
    (tmp_path / "tiny.bin").write_bytes(binary)
    (tmp_path / "tiny.gltf").write_text(json.dumps(document))
    scene = trimesh.load(tmp_path / "tiny.gltf")
    assert np.array_equal(scene.geometry["colored"].faces, [[0, 1, 2]])


@pytest.mark.parametrize("make, problem", [
    (lambda: b"glTX" + _glb(*_tiny_gltf())[4:], "magic"),
    (lambda: _glb(*_tiny_gltf())[:40], "bytes"),
    (lambda: _glb_raw(b"{]", b""), "JSON"),
    (lambda: _glb_raw(json.dumps({"asset": {"version": "1.0"}}).encode(), b""), "2.0"),
])
def test_malformed_glb_names_file_and_problem(tmp_path, make, problem):
    path = tmp_path / "bad.glb"
    path.write_bytes(make())
    with pytest.raises(ValueError, match=problem) as caught:
        trimesh.load(path)
    assert "bad.glb" in str(caught.value)


def test_gltf_index_past_vertices_is_an_error(tmp_path):
    document, binary = _tiny_gltf()
    document["accessors"][0]["count"] = 2
    path = tmp_path / "short.glb"
    path.write_bytes(_glb(document, binary))
    with pytest.raises(ValueError, match="short.glb"):
        trimesh.load(path)


def test_scene_add_geometry_and_dump():
    scene = trimesh.Scene()
    node = scene.add_geometry(trimesh.creation.box(), geom_name="box", transform=tf.translation_matrix([5, 0, 0]))
    scene.add_geometry(trimesh.creation.box(), geom_name="box", parent_node_name=node,
                       transform=tf.translation_matrix([0, 5, 0]))
    assert list(scene.geometry) == ["box", "box_1"]
    assert np.allclose(scene.bounds, [[4.5, -0.5, -0.5], [5.5, 5.5, 0.5]])
