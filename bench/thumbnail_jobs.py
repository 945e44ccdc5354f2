#!/usr/bin/env python3
"""thumbnail_jobs.py - the batch benchmarks' jobs file: N thumbnails cycling through six small real models of
Debian's assimp-testmodels (OBJ with and without textures, PLY, STL, COLLADA, GLB), each at its own azimuth and
elevation, writing out/NNNNNN.png. Usage: bench/thumbnail_jobs.py N SIZE > jobs.jsonl"""
import json
import sys

ROOT = "/usr/share/assimp/models"
MODELS = ["OBJ/WusonOBJ.obj", "OBJ/spider.obj", "PLY/Wuson.ply", "STL/Spider_binary.stl", "Collada/duck.dae",
          "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"]

count, size = int(sys.argv[1]), int(sys.argv[2])
for k in range(count):
    print(json.dumps({"model": f"{ROOT}/{MODELS[k % len(MODELS)]}", "output": f"out/{k:06}.png",
                      "resolution": [size, size], "camera-azimuth-angle": (k * 37) % 360,
                      "camera-elevation-angle": (k * 13) % 60 - 20}))
