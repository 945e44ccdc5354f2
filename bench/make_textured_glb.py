#!/usr/bin/env python3
"""make_textured_glb.py - the thumbnail benchmark's textured GLB: a 32,768-triangle UV sphere under a 640x640 PNG
base colour texture (bands and noise, which PNG barely compresses), 2.1 MB in all.
Usage: bench/make_textured_glb.py OUT.glb"""
import io
import json
import struct
import sys

import numpy as np
from PIL import Image

sys.path.insert(0, __import__("os").path.dirname(__file__))
from uv_sphere import uv_sphere  # noqa: E402


def texture_png(size):
    rng = np.random.default_rng(7)
    y, x = np.mgrid[0:size, 0:size]
    bands = np.stack([128 + 100 * np.sin(x / 23.0), 128 + 100 * np.sin(y / 31.0), 128 + 100 * np.cos((x + y) / 41.0)], -1)
    pixels = np.clip(bands + rng.normal(0, 24, bands.shape), 0, 255).astype(np.uint8)
    out = io.BytesIO()
    Image.fromarray(pixels).save(out, format="PNG")
    return out.getvalue()


def main(path):
    rings, segments = 128, 128
    positions, normals, faces = uv_sphere(rings, segments)
    t, s = np.meshgrid(np.linspace(0, 1, rings + 1), np.linspace(0, 1, segments + 1), indexing="ij")
    uvs = np.stack([s, t], -1).reshape(-1, 2)
    parts = [positions.astype("<f4").tobytes(), normals.astype("<f4").tobytes(), uvs.astype("<f4").tobytes(),
             faces.astype("<u4").tobytes(), texture_png(640)]
    views, offset = [], 0
    for part in parts:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part)})
        offset += (len(part) + 3) // 4 * 4
    binary = b"".join(p + b"\0" * ((4 - len(p) % 4) % 4) for p in parts)
    n = len(positions)
    gltf = {
        "asset": {"version": "2.0", "generator": "facet bench/make_textured_glb.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0,
                                                "roughnessFactor": 0.6}}],
        "textures": [{"source": 0}], "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "buffers": [{"byteLength": len(binary)}], "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": positions.min(0).tolist(), "max": positions.max(0).tolist()},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": faces.size, "type": "SCALAR"}],
    }
    text = json.dumps(gltf).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(binary), b"BIN\0") + binary)


if __name__ == "__main__":
    main(sys.argv[1])
