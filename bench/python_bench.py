#!/usr/bin/env python3
"""python_bench.py - a Python render against the same render through the C++ library, alternating rounds.

Usage: PYTHONPATH=build/python python3 bench/python_bench.py [BUILD_DIR] [ROUNDS]. Writes a UV sphere of
102,400 triangles as binary PLY, then per round times FRAMES frames of 640x480 (colour and depth returned as
arrays) with facet.OffscreenRenderer and with build/bench/facet_scene_frame_bench (the same view, lights and
read-back in C++), and prints a Markdown table of every round, the medians and the ratio.
"""
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import facet

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from uv_sphere import uv_sphere  # noqa: E402

WIDTH, HEIGHT, FRAMES, THREADS = 640, 480, 200, 2


def write_sphere(path, rings=160, segments=320):
    """The UV sphere as a binary PLY of positions and normals; returns its triangle count."""
    positions, normals, faces = uv_sphere(rings, segments)
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(normals)}\nproperty float x\n"
              f"property float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
              f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    vertices = np.hstack([positions, normals]).astype("<f4")
    face_records = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
    face_records["n"] = 3
    face_records["i"] = faces
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(vertices.tobytes())
        f.write(face_records.tobytes())
    return len(faces)


def python_round(renderer, scene):
    renderer.render(scene)
    start = time.perf_counter()
    for _ in range(FRAMES):
        color, depth = renderer.render(scene)
    assert color.shape == (HEIGHT, WIDTH, 3) and depth.shape == (HEIGHT, WIDTH)
    return (time.perf_counter() - start) * 1000.0 / FRAMES


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build")
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    cpp = build / "bench" / "facet_scene_frame_bench"
    with tempfile.TemporaryDirectory() as folder:
        model = os.path.join(folder, "sphere.ply")
        triangles = write_sphere(model)
        scene = facet.Scene()
        scene.add(facet.Mesh.from_file(model))
        pose = np.eye(4)
        pose[2, 3] = 3.0
        scene.add(facet.PerspectiveCamera(yfov=0.8, znear=0.5, zfar=10.0), pose=pose)
        renderer = facet.OffscreenRenderer(WIDTH, HEIGHT, threads=THREADS, samples=1)  # as the C++ bench draws
        rows = []
        for k in range(rounds):
            run_cpp = lambda: float(subprocess.run([str(cpp), model, str(WIDTH), str(HEIGHT), str(FRAMES),
                                                    str(THREADS)], check=True, capture_output=True,
                                                   text=True).stdout)
            if k % 2 == 0:
                c, p = run_cpp(), python_round(renderer, scene)
            else:
                p, c = python_round(renderer, scene), run_cpp()
            rows.append((c, p))
    print(f"sphere of {triangles} triangles, {WIDTH}x{HEIGHT}, {THREADS} threads, {FRAMES} frames per round")
    print("| round | C++ ms | Python ms | Python / C++ |\n|---|---:|---:|---:|")
    for k, (c, p) in enumerate(rows, 1):
        print(f"| {k} | {c:.3f} | {p:.3f} | {p / c:.3f} |")
    cm, pm = statistics.median(r[0] for r in rows), statistics.median(r[1] for r in rows)
    print(f"| median | {cm:.3f} | {pm:.3f} | {statistics.median(r[1] / r[0] for r in rows):.3f} |")


if __name__ == "__main__":
    main()
