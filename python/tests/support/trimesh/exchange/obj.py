"""Wavefront OBJ (with MTL materials and their diffuse images) read into a Trimesh, or a Scene per material."""
import collections
import io
import os
import warnings

import numpy as np
from PIL import Image

from ..base import Trimesh
from ..scene import Scene
from ..visual import ColorVisuals, TextureVisuals
from ..visual.material import SimpleMaterial

# map_* options and how many values each takes at most (-o, -s and -t take one to three numbers).
_MAP_OPTIONS = {"-blendu": 1, "-blendv": 1, "-bm": 1, "-boost": 1, "-cc": 1, "-clamp": 1, "-imfchan": 1,
                "-mm": 2, "-o": 3, "-s": 3, "-t": 3, "-texres": 1, "-type": 1}


def _floats(values, where, keyword, least):
    """`values` as floats, at least `least` of them; `where` ("file: line n") leads the error otherwise."""
    try:
        parsed = [float(v) for v in values]
    except ValueError:
        raise ValueError(f"{where}: '{keyword}' needs numbers, got {' '.join(values)!r}") from None
    if len(parsed) < least:
        raise ValueError(f"{where}: '{keyword}' needs at least {least} numbers, got {len(parsed)}")
    return parsed


def _raw_value(values):
    """An MTL value as trimesh users find it in SimpleMaterial.kwargs: a float, a list of floats, or text."""
    try:
        numbers = [float(v) for v in values]
    except ValueError:
        return " ".join(values)
    return numbers[0] if len(numbers) == 1 else numbers


def _mtl_color(values, where, keyword):
    """An MTL colour: r g b, where by the spec a missing g and b take r's value (so 'Ks 0' is black)."""
    numbers = _floats(values[:3], where, keyword, 1)
    return numbers + [numbers[0]] * (3 - len(numbers))


def _map_file(values):
    """The file name of a map_* statement: what is left after its options."""
    index = 0
    while index < len(values) and values[index] in _MAP_OPTIONS:
        most = _MAP_OPTIONS[values[index]]
        index += 1
        taken = 0
        while taken < most and index < len(values) - 1:
            if most > 1:
                try:
                    float(values[index])
                except ValueError:
                    break
            index += 1
            taken += 1
    return " ".join(values[index:]).replace("\\", "/")


def _read_image(path, mtl_name):
    """A PIL image read fully into memory, or None (with a warning) when the file is missing."""
    if not os.path.isfile(path):
        warnings.warn(f"{mtl_name}: texture {path} not found; the material has no image")
        return None
    try:
        with open(path, "rb") as handle:
            image = Image.open(io.BytesIO(handle.read()))
            image.load()
    except (OSError, ValueError) as error:
        raise ValueError(f"{mtl_name}: texture {path} is not a readable image ({error})") from None
    return image


def parse_mtl(text, name="<mtl>", folder=None):
    """Materials by name from MTL text; images are read relative to `folder` (not at all when it is None)."""
    materials = collections.OrderedDict()
    fields = None
    for number, line in enumerate(text.splitlines(), 1):
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        keyword, values = parts[0], parts[1:]
        if keyword == "newmtl":
            fields = {}
            materials[" ".join(values) or f"material_{len(materials)}"] = fields
        elif fields is None:
            raise ValueError(f"{name}: line {number}: '{keyword}' before any 'newmtl'")
        elif values:
            fields[keyword] = values
    result = collections.OrderedDict()
    for material_name, fields in materials.items():
        where = f"{name}: material {material_name!r}"
        color = {key: _mtl_color(fields[key], where, key) for key in ("Kd", "Ka", "Ks") if key in fields}
        diffuse = color.get("Kd")
        # 'd' is opacity by the MTL spec. 'Tr' is left raw: writers disagree on its sense (MeshLab writes 1 for
        # opaque), so applying it could make an opaque model vanish.
        if "d" in fields:
            diffuse = (diffuse or [0.4, 0.4, 0.4]) + [_floats(fields["d"][:1], where, "d", 1)[0]]
        image = None
        if "map_Kd" in fields and folder is not None:
            image = _read_image(os.path.join(folder, _map_file(fields["map_Kd"])), name)
        glossiness = _floats(fields["Ns"][:1], where, "Ns", 1)[0] if "Ns" in fields else None
        material = SimpleMaterial(image=image, diffuse=diffuse, ambient=color.get("Ka"), specular=color.get("Ks"),
                                  glossiness=glossiness, name=material_name)
        material.kwargs = {key: _raw_value(values) for key, values in fields.items()}
        result[material_name] = material
    return result


def _read_libraries(values, folder, name):
    """The materials of an 'mtllib' statement: one file name with spaces, or several names."""
    joined = os.path.join(folder, " ".join(values).replace("\\", "/"))
    paths = [joined] if os.path.isfile(joined) else [os.path.join(folder, v.replace("\\", "/")) for v in values]
    materials = collections.OrderedDict()
    for path in paths:
        if not os.path.isfile(path):
            warnings.warn(f"{name}: material library {path} not found")
            continue
        with open(path, "rb") as handle:
            materials.update(parse_mtl(handle.read().decode("utf-8", errors="replace"), path, os.path.dirname(path)))
    return materials


def _index(token, count, where, what):
    """A 0-based index from an OBJ index: 1-based, or negative counting back from the last one read so far."""
    try:
        value = int(token)
    except ValueError:
        raise ValueError(f"{where}: bad {what} index {token!r}") from None
    resolved = value - 1 if value > 0 else count + value
    if value == 0 or not 0 <= resolved < count:
        raise ValueError(f"{where}: {what} index {value} outside the {count} read so far")
    return resolved


def _build(corners, positions, uvs, normals, colors, material, keep_all):
    """A Trimesh from triangle corners (M x 3 of vertex, uv, normal index, -1 for none). Vertices are split per
    unique (vertex, uv) pair, so each carries one uv, unless `keep_all` keeps the file's vertices as they are."""
    if keep_all:
        order = np.arange(len(positions))
        remap = corners[:, 0]
    else:
        keys = corners[:, 0] * (len(uvs) + 1) + corners[:, 1] + 1
        _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
        # Number the new vertices by first use, so they follow the file's order.
        rank = np.empty(len(first), dtype=np.int64)
        rank[np.argsort(first, kind="stable")] = np.arange(len(first))
        remap = rank[inverse.reshape(-1)]
        order = np.empty(len(first), dtype=np.int64)
        order[rank] = first
        order = corners[order, 0]
    source = np.full(len(order), -1, dtype=np.int64)
    source[remap[::-1]] = np.arange(len(corners))[::-1]
    mesh_normals = None
    if len(normals) and np.all(source >= 0) and np.all(corners[source, 2] >= 0):
        mesh_normals = normals[corners[source, 2]]
    mesh = Trimesh(vertices=positions[order], faces=remap.reshape(-1, 3), vertex_normals=mesh_normals)
    has_uv = len(uvs) > 0 and np.any(corners[:, 1] >= 0)
    if material is not None and has_uv:
        picked = np.where(source >= 0, corners[np.maximum(source, 0), 1], -1)
        uv = np.where(picked[:, np.newaxis] >= 0, uvs[np.maximum(picked, 0)], 0.0)
        mesh.visual = TextureVisuals(uv=uv, material=material)
    elif material is not None:
        mesh.visual = TextureVisuals(material=material)
    elif colors is not None:
        mesh.visual = ColorVisuals(vertex_colors=colors[order])
    return mesh


def load_obj(file_obj, name="<obj>", folder=None, **kwargs):
    """A Trimesh from OBJ data, or a Scene with one geometry per material when faces use several. MTL files and
    textures are looked up in `folder` (the OBJ's); a missing one only costs the material (with a warning)."""
    data = file_obj.read()
    if isinstance(data, bytes):
        # Some exporters write UTF-16 with a byte order mark; everything else is read as UTF-8.
        utf16 = data[:2] in (b"\xff\xfe", b"\xfe\xff")
        text = data.decode("utf-16" if utf16 else "utf-8", errors="replace")
    else:
        text = data
    positions, colors, uvs, normals = [], [], [], []
    groups = collections.OrderedDict()
    materials = collections.OrderedDict()
    current = None
    for number, line in enumerate(text.splitlines(), 1):
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        keyword, values = parts[0], parts[1:]
        where = f"{name}: line {number}"
        if keyword == "v":
            numbers = _floats(values, where, "v", 3)
            positions.append(numbers[:3])
            colors.append(numbers[3:6] if len(numbers) >= 6 else None)
        elif keyword == "vt":
            uvs.append((_floats(values, where, "vt", 1) + [0.0])[:2])
        elif keyword == "vn":
            normals.append(_floats(values, where, "vn", 3)[:3])
        elif keyword == "f":
            if len(values) < 3:
                raise ValueError(f"{where}: a face needs at least 3 corners, got {len(values)}")
            polygon = []
            for token in values:
                fields = token.split("/")
                if len(fields) > 3 or not fields[0]:
                    raise ValueError(f"{where}: bad face corner {token!r}")
                fields += [""] * (3 - len(fields))
                polygon.append((_index(fields[0], len(positions), where, "vertex"),
                                _index(fields[1], len(uvs), where, "uv") if fields[1] else -1,
                                _index(fields[2], len(normals), where, "normal") if fields[2] else -1))
            # A polygon becomes a fan of triangles around its first corner.
            groups.setdefault(current, []).extend(
                corner for i in range(1, len(polygon) - 1) for corner in (polygon[0], polygon[i], polygon[i + 1]))
        elif keyword == "usemtl":
            current = " ".join(values) or None
        elif keyword == "mtllib" and folder is not None:
            materials.update(_read_libraries(values, folder, name))
    if not positions:
        raise ValueError(f"{name}: no vertices ('v' lines) found")
    positions = np.array(positions, dtype=np.float64)
    colors = np.array(colors, dtype=np.float64) if all(c is not None for c in colors) else None
    if colors is not None and colors.max() > 1.0:
        # Some exporters write vertex colours as 0..255 rather than the usual 0..1.
        colors = colors / 255.0
    uvs = np.array(uvs, dtype=np.float64).reshape(-1, 2)
    normals = np.array(normals, dtype=np.float64).reshape(-1, 3)
    if not groups:
        groups[None] = []
    meshes = collections.OrderedDict()
    keep_all = len(groups) == 1 and len(uvs) == 0
    for material_name, corners in groups.items():
        corners = np.array(corners, dtype=np.int64).reshape(-1, 3)
        material = materials.get(material_name)
        if material_name is not None and material is None:
            warnings.warn(f"{name}: material {material_name!r} is not in any material library")
        mesh = _build(corners, positions, uvs, normals, colors, material, keep_all)
        mesh.metadata.update(name=name, file_name=os.path.basename(name))
        meshes[material_name or os.path.splitext(os.path.basename(name))[0] or "geometry"] = mesh
    if len(meshes) == 1:
        return next(iter(meshes.values()))
    scene = Scene()
    for geom_name, mesh in meshes.items():
        scene.add_geometry(mesh, geom_name=geom_name)
    return scene
