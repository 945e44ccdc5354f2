"""Draws every scene of pyrender_scenes with the module named (pyrender or facet) into an .npz of colour and depth.

Usage: python3 render_with.py MODULE OUT.npz   (pyrender's needs PYOPENGL_PLATFORM=egl and its source on PYTHONPATH)
"""
import importlib
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pyrender_scenes  # noqa: E402

module, out = sys.argv[1], sys.argv[2]
images = pyrender_scenes.render_all(importlib.import_module(module))
np.savez_compressed(out, **{f"{name}_{kind}": array for name, pair in images.items()
                            for kind, array in zip(("color", "depth"), pair)})
