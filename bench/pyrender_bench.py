#!/usr/bin/env python3
"""pyrender_bench.py - facet against pyrender (Mesa's llvmpipe through EGL) as Python users time them, alternating.

Usage: PYTHONPATH=build/python python3 bench/pyrender_bench.py PYRENDER_CHECKOUT [ROUNDS]
The same calls in both (pyrender's API): a sphere of 200,704 triangles as one Primitive, a directional light and a
perspective camera, 640x480, colour and depth returned, 4x multisampling (pyrender's), 2 threads each (facet's
threads=2, llvmpipe's LP_NUM_THREADS=2). Per round and renderer: the first image, timed as a whole process
(interpreter, imports with their bytecode compiled by a warm-up run, scene, renderer, one frame), and the steady frame, the mean of FRAMES frames after one.
Prints a Markdown table of the medians and the ratios. pyrender needs Debian's python3-opengl, -pyglet, -scipy,
-networkx, -imageio, -freetype and -pil (scripts/pyrender_compare.sh installs them).
"""
import os
import statistics
import subprocess
import sys
import time

WIDTH, HEIGHT, FRAMES, THREADS = 640, 480, 50, 2
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from uv_sphere import uv_sphere  # noqa: E402
SUPPORT = os.path.join(HERE, "..", "python", "tests", "support")


def child(module, mode):
    """Runs in its own process: builds the scene with `module` standing in for pyrender and renders."""
    import importlib
    import numpy as np
    pr = importlib.import_module(module)
    positions, normals, faces = uv_sphere(224, 448)
    scene = pr.Scene(bg_color=[0.0, 0.0, 0.0, 1.0], ambient_light=[0.1, 0.1, 0.1])
    material = pr.MetallicRoughnessMaterial(baseColorFactor=[0.8, 0.5, 0.3, 1.0], metallicFactor=0.0,
                                            roughnessFactor=0.5)
    scene.add(pr.Mesh([pr.Primitive(positions=positions, normals=normals, indices=faces, material=material)]))
    pose = np.eye(4)
    pose[2, 3] = 3.0
    scene.add(pr.PerspectiveCamera(yfov=0.8, znear=0.5, zfar=10.0), pose=pose)
    scene.add(pr.DirectionalLight(intensity=3.0), pose=pose)
    extra = {"threads": THREADS} if module == "facet" else {}
    renderer = pr.OffscreenRenderer(WIDTH, HEIGHT, **extra)
    color, depth = renderer.render(scene)
    assert color.shape == (HEIGHT, WIDTH, 3) and (depth > 0).sum() > 50000
    if mode == "steady":
        start = time.perf_counter()
        for _ in range(FRAMES):
            renderer.render(scene)
        print((time.perf_counter() - start) * 1000.0 / FRAMES)
    renderer.delete()


def run(module, mode, source):
    paths = [SUPPORT, source] if module == "pyrender" else [SUPPORT]
    env = dict(os.environ, PYOPENGL_PLATFORM="egl", LP_NUM_THREADS=str(THREADS),
               PYTHONPATH=os.pathsep.join(paths + [os.environ.get("PYTHONPATH", "")]))
    # Modules compiled once, as an installed package's are: the warm-up run writes their bytecode.
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    start = time.perf_counter()
    out = subprocess.run([sys.executable, os.path.abspath(__file__), "--child", module, mode], env=env, check=True,
                         capture_output=True, text=True).stdout
    wall = (time.perf_counter() - start) * 1000.0
    return wall if mode == "first" else float(out)


def main():
    if sys.argv[1:2] == ["--child"]:
        child(sys.argv[2], sys.argv[3])
        return
    source = os.path.abspath(sys.argv[1])
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    times = {(m, k): [] for m in ("facet", "pyrender") for k in ("first", "steady")}
    for module in ("facet", "pyrender"):
        run(module, "first", source)
    for r in range(rounds):
        order = ("facet", "pyrender") if r % 2 == 0 else ("pyrender", "facet")
        for mode in ("first", "steady"):
            for module in order:
                times[(module, mode)].append(run(module, mode, source))
    med = {key: statistics.median(values) for key, values in times.items()}
    print(f"sphere of 200,704 triangles, {WIDTH}x{HEIGHT}, 4x MSAA, {THREADS} threads, {rounds} alternated rounds")
    print("| | facet ms | pyrender ms | pyrender / facet |\n|---|---:|---:|---:|")
    for mode, label in (("first", "first image (whole process)"), ("steady", f"steady frame (mean of {FRAMES})")):
        f, p = med[("facet", mode)], med[("pyrender", mode)]
        print(f"| {label} | {f:.1f} | {p:.1f} | {p / f:.2f} |")


if __name__ == "__main__":
    main()
