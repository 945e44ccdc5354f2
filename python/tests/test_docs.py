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
