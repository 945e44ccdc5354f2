"""glTF 2.0 (.gltf JSON or .glb binary) read into a Scene: triangle primitives, PBR materials, the node tree."""
import base64
import io
import json
import os
import struct
import warnings

import numpy as np
from PIL import Image

from .. import transformations
from ..base import Trimesh
from ..scene import Scene, _unique_name
from ..visual import ColorVisuals, TextureVisuals
from ..visual.material import PBRMaterial

_COMPONENTS = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
_WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}
_CHUNK_JSON, _CHUNK_BIN = 0x4E4F534A, 0x004E4942
# Required extensions that change nothing this reader relies on; any other required one cannot be honoured.
_HARMLESS_EXTENSIONS = {"KHR_mesh_quantization", "KHR_materials_unlit", "KHR_texture_transform",
                        "KHR_materials_emissive_strength"}


def _normalize(values):
    """Integer data as the 0..1 (or -1..1) floats that glTF's `normalized` flag stands for."""
    if values.dtype.kind == "f":
        return values.astype(np.float64)
    top = float(np.iinfo(values.dtype).max)
    return np.maximum(values.astype(np.float64) / top, -1.0)


class _Reader:
    """Decodes one glTF document; every failure names the file."""

    def __init__(self, document, binary, name, folder):
        self.doc, self.binary, self.name, self.folder = document, binary, name, folder
        self._buffers, self._images, self._materials = {}, {}, {}

    def fail(self, message):
        raise ValueError(f"{self.name}: {message}")

    def _uri_bytes(self, uri, what):
        if uri.startswith("data:"):
            header, _, payload = uri.partition(",")
            if not header.endswith(";base64"):
                self.fail(f"{what}: only base64 data URIs are supported")
            return base64.b64decode(payload)
        if self.folder is None:
            self.fail(f"{what}: external file {uri!r} but no folder to find it in")
        path = os.path.join(self.folder, uri)
        if not os.path.isfile(path):
            return None
        with open(path, "rb") as handle:
            return handle.read()

    def buffer(self, index):
        if index not in self._buffers:
            entry = self.doc["buffers"][index]
            if "uri" in entry:
                data = self._uri_bytes(entry["uri"], f"buffer {index}")
                if data is None:
                    self.fail(f"buffer {index}: file {entry['uri']!r} not found")
            elif index == 0 and self.binary is not None:
                data = self.binary
            else:
                self.fail(f"buffer {index} has no uri and there is no binary chunk")
            if len(data) < entry.get("byteLength", 0):
                self.fail(f"buffer {index} holds {len(data)} bytes, fewer than its byteLength {entry['byteLength']}")
            self._buffers[index] = data
        return self._buffers[index]

    def view_bytes(self, index):
        view = self.doc["bufferViews"][index]
        data = self.buffer(view["buffer"])
        start = view.get("byteOffset", 0)
        end = start + view["byteLength"]
        if end > len(data):
            self.fail(f"bufferView {index} ends at byte {end}, past its buffer's {len(data)}")
        return memoryview(data)[start:end], view.get("byteStride")

    def _read(self, view_index, offset, component, width, count, what):
        if component not in _COMPONENTS:
            self.fail(f"{what}: unknown componentType {component}")
        dtype = np.dtype(_COMPONENTS[component]).newbyteorder("<")
        if count == 0:
            return np.zeros((0, width), dtype=dtype.newbyteorder("="))
        data, stride = self.view_bytes(view_index)
        element = dtype.itemsize * width
        stride = stride or element
        needed = offset + stride * (count - 1) + element
        if needed > len(data):
            self.fail(f"{what}: {count} elements need {needed} bytes of bufferView {view_index}, it has {len(data)}")
        values = np.ndarray((count, width), dtype=dtype, buffer=data, offset=offset, strides=(stride, dtype.itemsize))
        return values.astype(dtype.newbyteorder("="))

    def accessor(self, index, normalize=False):
        """The accessor's data, count x width (count for scalars), with sparse substitutions applied; integers
        become floats when the accessor says `normalized` or `normalize` asks for it."""
        entry = self.doc["accessors"][index]
        what = f"accessor {index}"
        if entry.get("type") not in _WIDTHS:
            self.fail(f"{what}: unknown type {entry.get('type')!r}")
        width, count, component = _WIDTHS[entry["type"]], entry["count"], entry["componentType"]
        if "bufferView" in entry:
            values = self._read(entry["bufferView"], entry.get("byteOffset", 0), component, width, count, what)
        elif component in _COMPONENTS:
            values = np.zeros((count, width), dtype=_COMPONENTS[component])
        else:
            self.fail(f"{what}: unknown componentType {component}")
        sparse = entry.get("sparse")
        if sparse:
            where = sparse["indices"]
            rows = self._read(where["bufferView"], where.get("byteOffset", 0), where["componentType"], 1,
                              sparse["count"], f"{what} sparse indices").reshape(-1)
            if rows.size and rows.max() >= count:
                self.fail(f"{what}: sparse index {rows.max()} past its {count} elements")
            replacement = sparse["values"]
            values[rows] = self._read(replacement["bufferView"], replacement.get("byteOffset", 0), component, width,
                                      sparse["count"], f"{what} sparse values")
        if entry.get("normalized") or normalize:
            values = _normalize(values)
        return values.reshape(-1) if width == 1 else values

    def image(self, index):
        if index not in self._images:
            entry = self.doc["images"][index]
            if "bufferView" in entry:
                data = bytes(self.view_bytes(entry["bufferView"])[0])
            elif "uri" in entry:
                data = self._uri_bytes(entry["uri"], f"image {index}")
            else:
                self.fail(f"image {index} has neither a bufferView nor a uri")
            image = None
            if data is None:
                warnings.warn(f"{self.name}: image {index} file {entry['uri']!r} not found; texture left out")
            else:
                try:
                    image = Image.open(io.BytesIO(data))
                    image.load()
                except (OSError, ValueError) as error:
                    self.fail(f"image {index} cannot be decoded ({error})")
            self._images[index] = image
        return self._images[index]

    def texture(self, info):
        """The PIL image a textureInfo points at, or None."""
        if not info:
            return None
        texture = self.doc["textures"][info["index"]]
        source = texture.get("source")
        if source is None:
            # Textures in other formats name their image in an extension; take the first that does.
            sources = [ext.get("source") for ext in texture.get("extensions", {}).values() if isinstance(ext, dict)]
            source = next((s for s in sources if s is not None), None)
        return None if source is None else self.image(source)

    def material(self, index):
        if index not in self._materials:
            entry = self.doc["materials"][index]
            pbr = entry.get("pbrMetallicRoughness", {})
            try:
                self._materials[index] = PBRMaterial(
                    name=entry.get("name"),
                    baseColorFactor=pbr.get("baseColorFactor"),
                    metallicFactor=pbr.get("metallicFactor"),
                    roughnessFactor=pbr.get("roughnessFactor"),
                    baseColorTexture=self.texture(pbr.get("baseColorTexture")),
                    metallicRoughnessTexture=self.texture(pbr.get("metallicRoughnessTexture")),
                    normalTexture=self.texture(entry.get("normalTexture")),
                    occlusionTexture=self.texture(entry.get("occlusionTexture")),
                    emissiveTexture=self.texture(entry.get("emissiveTexture")),
                    emissiveFactor=entry.get("emissiveFactor"),
                    doubleSided=entry.get("doubleSided", False),
                    alphaMode=entry.get("alphaMode"),
                    alphaCutoff=entry.get("alphaCutoff"))
            except ValueError as error:
                self.fail(f"material {index}: {error}")
        return self._materials[index]

    def primitive(self, mesh_index, primitive_index):
        """A Trimesh of one primitive, or None for points and lines (which a Trimesh cannot hold)."""
        primitive = self.doc["meshes"][mesh_index]["primitives"][primitive_index]
        what = f"mesh {mesh_index} primitive {primitive_index}"
        attributes = primitive["attributes"]
        if "POSITION" not in attributes:
            self.fail(f"{what} has no POSITION")
        mode = primitive.get("mode", 4)
        if mode not in (4, 5, 6):
            warnings.warn(f"{self.name}: {what} draws points or lines (mode {mode}); left out")
            return None
        positions = self.accessor(attributes["POSITION"]).astype(np.float64)
        if "indices" in primitive:
            corners = self.accessor(primitive["indices"]).astype(np.int64).reshape(-1)
        else:
            corners = np.arange(len(positions), dtype=np.int64)
        if mode == 4:
            if len(corners) % 3:
                self.fail(f"{what}: {len(corners)} indices do not make whole triangles")
            faces = corners.reshape(-1, 3)
        elif mode == 5:
            # A strip flips winding on every other triangle; swapping the first two corners there undoes that.
            i = np.arange(max(len(corners) - 2, 0))
            odd = i % 2 == 1
            faces = np.column_stack([np.where(odd, corners[i + 1], corners[i]),
                                     np.where(odd, corners[i], corners[i + 1]), corners[i + 2]])
        else:
            i = np.arange(1, max(len(corners) - 1, 1))
            faces = np.column_stack([np.full(len(i), corners[0]), corners[i], corners[i + 1]])
        if faces.size and (faces.min() < 0 or faces.max() >= len(positions)):
            self.fail(f"{what}: index {faces.max()} past its {len(positions)} vertices")
        normals = self.accessor(attributes["NORMAL"]).astype(np.float64) if "NORMAL" in attributes else None
        mesh = Trimesh(vertices=positions, faces=faces, vertex_normals=normals)
        material = self.material(primitive["material"]) if "material" in primitive else None
        if "TEXCOORD_0" in attributes and material is not None:
            uv = self.accessor(attributes["TEXCOORD_0"], normalize=True)
            # glTF puts v=0 at the image's top; trimesh's uvs have v=0 at the bottom, as OBJ's do.
            uv[:, 1] = 1.0 - uv[:, 1]
            mesh.visual = TextureVisuals(uv=uv, material=material)
        elif "COLOR_0" in attributes:
            mesh.visual = ColorVisuals(vertex_colors=self.accessor(attributes["COLOR_0"], normalize=True))
        elif material is not None:
            mesh.visual = TextureVisuals(material=material)
        return mesh

    def local_matrix(self, node, index):
        if "matrix" in node:
            values = np.asarray(node["matrix"], dtype=np.float64)
            if values.size != 16:
                self.fail(f"node {index}: matrix has {values.size} numbers, not 16")
            return values.reshape(4, 4).T
        x, y, z, w = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
        scale = np.diag(list(node.get("scale", [1.0, 1.0, 1.0])) + [1.0])
        return (transformations.translation_matrix(node.get("translation", [0.0, 0.0, 0.0]))
                @ transformations.quaternion_matrix([w, x, y, z]) @ scale)

    def scene(self):
        extensions = set(self.doc.get("extensionsRequired", [])) - _HARMLESS_EXTENSIONS
        if extensions:
            self.fail(f"requires unsupported extensions {sorted(extensions)}")
        scene = Scene()
        scene.metadata["name"] = self.name
        primitive_names = []
        for mesh_index, mesh in enumerate(self.doc.get("meshes", [])):
            names = []
            for primitive_index in range(len(mesh["primitives"])):
                geometry = self.primitive(mesh_index, primitive_index)
                if geometry is None:
                    names.append(None)
                    continue
                geom_name = _unique_name(mesh.get("name") or f"mesh_{mesh_index}", scene.geometry)
                geometry.metadata["name"] = geom_name
                scene.geometry[geom_name] = geometry
                names.append(geom_name)
            primitive_names.append(names)
        nodes = self.doc.get("nodes", [])
        scenes = self.doc.get("scenes")
        if scenes:
            roots = scenes[self.doc.get("scene", 0)].get("nodes", [])
        else:
            children = {child for node in nodes for child in node.get("children", [])}
            roots = [i for i in range(len(nodes)) if i not in children]
        stack = [(index, scene.graph.base_frame) for index in reversed(roots)]
        visited = set()
        while stack:
            index, parent = stack.pop()
            if index in visited:
                self.fail(f"node {index} has more than one parent or is its own ancestor")
            visited.add(index)
            node = nodes[index]
            node_name = _unique_name(node.get("name") or f"node_{index}", set(scene.graph.nodes))
            placed = [n for n in primitive_names[node["mesh"]] if n is not None] if "mesh" in node else []
            scene.graph.update(node_name, frame_from=parent, matrix=self.local_matrix(node, index),
                               geometry=placed[0] if len(placed) == 1 else None)
            if len(placed) > 1:
                # One child node per primitive, as a node can place only one geometry.
                for geom_name in placed:
                    child = _unique_name(f"{node_name}_{geom_name}", set(scene.graph.nodes))
                    scene.graph.update(child, frame_from=node_name, matrix=np.eye(4), geometry=geom_name)
            stack.extend((child, node_name) for child in reversed(node.get("children", [])))
        return scene


def _split_glb(data, name):
    """(JSON document, binary chunk or None) of a GLB container."""
    if len(data) < 20 or data[:4] != b"glTF":
        raise ValueError(f"{name}: not a GLB file (no 'glTF' magic)")
    version, length = struct.unpack_from("<II", data, 4)
    if version != 2:
        raise ValueError(f"{name}: GLB version {version}; only glTF 2.0 is supported")
    if length > len(data):
        raise ValueError(f"{name}: GLB says {length} bytes but the file has {len(data)}")
    chunks, offset = {}, 12
    while offset + 8 <= length:
        size, kind = struct.unpack_from("<II", data, offset)
        start, offset = offset + 8, offset + 8 + size
        if offset > length:
            raise ValueError(f"{name}: GLB chunk at byte {start - 8} runs past the end of the file")
        chunks.setdefault(kind, data[start:offset])
    if _CHUNK_JSON not in chunks:
        raise ValueError(f"{name}: GLB has no JSON chunk")
    return chunks[_CHUNK_JSON], chunks.get(_CHUNK_BIN)


def load_gltf(file_obj, name="<gltf>", folder=None, file_type=None, **kwargs):
    """A Scene from glTF 2.0 data, binary (GLB, which file_type 'glb' insists on) or JSON; external buffers and
    images are found in `folder`."""
    data = file_obj.read()
    if isinstance(data, str):
        data = data.encode("utf-8")
    is_binary = data[:4] == b"glTF" or file_type == "glb"
    text, binary = _split_glb(data, name) if is_binary else (data, None)
    try:
        document = json.loads(bytes(text).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise ValueError(f"{name}: the glTF JSON cannot be parsed ({error})") from None
    if not isinstance(document, dict):
        raise ValueError(f"{name}: the glTF JSON is not an object")
    version = str(document.get("asset", {}).get("version", ""))
    if not version.startswith("2"):
        raise ValueError(f"{name}: asset version {version!r}; only glTF 2.0 is supported")
    try:
        return _Reader(document, binary, name, folder).scene()
    except (KeyError, IndexError, TypeError, AttributeError) as error:
        raise ValueError(f"{name}: malformed glTF ({type(error).__name__}: {error})") from None
