"""test_docs.py - the examples of docs/PYTHON.md run as written, on a real model."""
import pathlib
import re

import numpy as np

DOC = pathlib.Path(__file__).resolve().parents[2] / "docs" / "PYTHON.md"
MODEL = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"


def example(heading):
    text = DOC.read_text()
    return re.search(rf"## {re.escape(heading)}\n.*?```python\n(.*?)```", text, re.S).group(1)


def test_the_scene_example_renders(tmp_path):
    names = {}
    exec(example("A scene, a camera, a frame").replace('"model.glb"', repr(MODEL)), names)
    assert names["color"].shape == (480, 640, 3) and names["depth"].shape == (480, 640)


def test_the_dataset_example_writes_every_view(tmp_path):
    code = example("A dataset: N views of a model").replace('"model.glb"', repr(MODEL))
    code = code.replace('pathlib.Path("views")', f"pathlib.Path({str(tmp_path / 'views')!r})")
    exec(code, {})
    views = sorted((tmp_path / "views").glob("view_*.npz"))
    assert len(views) == 24 and len(list((tmp_path / "views").glob("view_*.json"))) == 24
    first = np.load(views[0])
    assert set(first.files) == {"color", "depth", "normal", "ids", "mask"}
    assert (first["mask"] == 255).any()


def test_the_materials_and_lights_example_renders():
    names = {}
    exec(example("Materials and lights"), names)
    color, depth = names["color"], names["depth"]
    assert color.shape == (480, 640, 3) and (depth > 0).mean() > 0.2
    # The floor right below the spot, (0, 0, 0.5), shows at pixel (359, 320), and (-1.5, 0, -1.5), outside the
    # cone, at (316, 207): the spot's disc is far brighter than the floor outside it.
    below, outside = color[355:364, 316:325].mean(), color[312:321, 203:212].mean()
    assert (depth[312:321, 203:212] > 0).all() and below > 3 * outside + 30
