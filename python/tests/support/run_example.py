"""Runs pyrender's examples/example.py with the module named standing in for pyrender, its viewer and pyglet lines
left out and its matplotlib figures kept as arrays, and saves the offscreen colour, depth and segmentation.

Usage: python3 run_example.py MODULE EXAMPLES_DIR OUT.npz
"""
import importlib
import os
import sys
import types

import numpy as np

module, examples, out = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.modules["pyrender"] = importlib.import_module(module)

shown = []
pyplot = types.ModuleType("matplotlib.pyplot")
pyplot.figure = pyplot.show = lambda *args, **kwargs: None
pyplot.imshow = lambda image, *args, **kwargs: shown.append(np.asarray(image))
sys.modules["matplotlib"] = types.ModuleType("matplotlib")
sys.modules["matplotlib.pyplot"] = pyplot

# The lines an on-screen window needs, which an offscreen renderer has no use for: pyglet's and the viewer's.
kept = [line for line in open(os.path.join(examples, "example.py")).read().splitlines()
        if "pyglet" not in line and "Viewer(" not in line]
source = "\n".join(kept).replace("Viewer, ", "")
os.chdir(examples)
np.random.seed(0)
namespace = {"__name__": "__main__"}
exec(compile(source, "example.py", "exec"), namespace)
color, depth = namespace["color"], namespace["depth"]
np.savez_compressed(out, color=color, depth=depth, seg=shown[-1])
