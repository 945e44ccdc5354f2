"""test_dask.py - facet.render mapped over model files on a dask.distributed LocalCluster of worker processes, as
docs/PYTHON.md shows it: the workers' images equal the ones rendered in this process."""
import os
import pathlib
import re
import shutil

import distributed  # Debian's python3-distributed, which scripts/deps.sh installs
import numpy as np
import pytest

import facet

# distributed 2022.12 on Debian 12's tornado: its own deprecation warnings, nothing of facet's.
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

MODELS = "/usr/share/assimp/models"
FILES = [f"{MODELS}/OBJ/WusonOBJ.obj", f"{MODELS}/PLY/Wuson.ply", f"{MODELS}/STL/Spider_binary.stl",
         f"{MODELS}/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", f"{MODELS}/Collada/duck.dae"]


def test_local_cluster_renders_what_one_process_renders():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        futures = client.map(facet.render, FILES, width=128, height=96, buffers=["color", "mask"])
        results = client.gather(futures)
        workers = set(client.run(os.getpid).values())
    assert len(workers) == 2 and os.getpid() not in workers, "two worker processes of their own"
    for path, remote in zip(FILES, results):
        local = facet.render(path, width=128, height=96, buffers=["color", "mask"])
        assert remote["color"].shape == (96, 128, 3), path
        assert remote["mask"].any(), f"{path}: nothing drawn"
        assert np.array_equal(remote["color"], local["color"]), path
        assert np.array_equal(remote["mask"], local["mask"]), path


def test_a_bad_file_raises_in_the_caller():
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        future = client.submit(facet.render, f"{MODELS}/OBJ/missing.obj", width=32, height=32)
        with pytest.raises(Exception, match="missing.obj"):
            future.result()


def test_the_documented_example_writes_every_model(tmp_path, monkeypatch):
    doc = pathlib.Path(__file__).resolve().parents[2] / "docs" / "PYTHON.md"
    code = re.search(r"## Many files on many processes: Dask\n.*?```python\n(.*?)```", doc.read_text(), re.S).group(1)
    models = tmp_path / "models"
    models.mkdir()
    for name in ("2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "BoxTextured-glTF-Binary/BoxTextured.glb"):
        shutil.copy(f"{MODELS}/glTF2/{name}", models)
    monkeypatch.chdir(tmp_path)
    exec(code, {"__name__": "__main__"})
    for glb in sorted(models.glob("*.glb")):
        written = np.load(glb.with_suffix(".npz"))
        assert np.array_equal(written["color"], facet.render(str(glb), width=256, height=256)["color"]), glb
