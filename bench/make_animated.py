#!/usr/bin/env python3
"""make_animated.py - writes a skinned, animated GLB for the animation benchmarks: a tube of RINGS x SIDES vertices
standing on +y, in a chain of BONES bones that sway through a 4 s clip.

Usage: make_animated.py OUT.glb [RINGS SIDES BONES]   (default 200 64 8: 12,800 vertices, 25,344 triangles)
Plain python3: no numpy.
"""
import json
import math
import struct
import sys


def tube(rings, sides, bones, height=4.0, radius=0.3):
    positions, normals, joints, weights, indices = [], [], [], [], []
    bone_length = height / bones
    for r in range(rings):
        y = height * r / (rings - 1)
        # Each vertex follows the two bones around it, by how near their middles it lies.
        at = min(max(y / bone_length - 0.5, 0.0), bones - 1.0)
        lower = min(int(at), bones - 2) if bones > 1 else 0
        upper_weight = min(max(at - lower, 0.0), 1.0) if bones > 1 else 0.0
        for s in range(sides):
            a = 2 * math.pi * s / sides
            positions += [radius * math.cos(a), y, radius * math.sin(a)]
            normals += [math.cos(a), 0.0, math.sin(a)]
            joints += [lower, min(lower + 1, bones - 1), 0, 0]
            weights += [1.0 - upper_weight, upper_weight, 0.0, 0.0]
    for r in range(rings - 1):
        for s in range(sides):
            a, b = r * sides + s, r * sides + (s + 1) % sides
            c, d = a + sides, b + sides
            indices += [a, c, b, b, c, d]
    return positions, normals, joints, weights, indices


def main():
    out = sys.argv[1]
    rings, sides, bones = (int(v) for v in (sys.argv[2:5] if len(sys.argv) >= 5 else (200, 64, 8)))
    positions, normals, joints, weights, indices = tube(rings, sides, bones)
    bone_length = 4.0 / bones
    keys = [0.25 * k for k in range(17)]
    rotations = []
    for t in keys:
        for b in range(bones):
            half = 0.5 * 0.25 * math.sin(2 * math.pi * t / 4.0 + 0.6 * b)
            rotations.append([0.0, 0.0, math.sin(half), math.cos(half)])
    chunks, views, accessors = [], [], []

    def add(data, fmt, count, kind, component, extra=None):
        blob = struct.pack(f"<{len(data)}{fmt}", *data)
        offset = sum(len(c) for c in chunks)
        chunks.append(blob + b"\0" * (-len(blob) % 4))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob)})
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
        accessor.update(extra or {})
        accessors.append(accessor)
        return len(accessors) - 1

    n = len(positions) // 3
    xs, ys, zs = positions[0::3], positions[1::3], positions[2::3]
    position = add(positions, "f", n, "VEC3", 5126,
                   {"min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]})
    normal = add(normals, "f", n, "VEC3", 5126)
    joint = add(joints, "H", n, "VEC4", 5123)
    weight = add(weights, "f", n, "VEC4", 5126)
    index = add(indices, "I", len(indices), "SCALAR", 5125)
    inverse_binds = []
    for b in range(bones):  # column-major: a translation by -(the bone's base height) along y
        inverse_binds += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -b * bone_length, 0, 1]
    ibm = add(inverse_binds, "f", bones, "MAT4", 5126)
    times = add(keys, "f", len(keys), "SCALAR", 5126, {"min": [keys[0]], "max": [keys[-1]]})
    samplers, channels = [], []
    for b in range(bones):
        values = [v for k in range(len(keys)) for v in rotations[k * bones + b]]
        samplers.append({"input": times, "output": add(values, "f", len(keys), "VEC4", 5126)})
        channels.append({"sampler": b, "target": {"node": 1 + b, "path": "rotation"}})
    nodes = [{"mesh": 0, "skin": 0, "name": "tube"}]
    for b in range(bones):
        node = {"name": f"bone{b}", "translation": [0, 0 if b == 0 else bone_length, 0]}
        if b + 1 < bones:
            node["children"] = [2 + b]
        nodes.append(node)
    gltf = {
        "asset": {"version": "2.0", "generator": "facet bench/make_animated.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": position, "NORMAL": normal, "JOINTS_0": joint,
                                                   "WEIGHTS_0": weight}, "indices": index, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.1, 1], "metallicFactor": 0.0,
                                                "roughnessFactor": 0.5}}],
        "skins": [{"joints": list(range(1, 1 + bones)), "inverseBindMatrices": ibm}],
        "animations": [{"name": "Sway", "samplers": samplers, "channels": channels}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": sum(len(c) for c in chunks)}],
    }
    body = b"".join(chunks)
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    with open(out, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(body)))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(body), b"BIN\0") + body)


if __name__ == "__main__":
    main()
