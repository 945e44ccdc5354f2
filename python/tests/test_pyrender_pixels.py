"""The same calls give the same picture: scenes made with pyrender's API, drawn by pyrender itself (on Mesa's
llvmpipe through EGL) and by facet, agree within a mean of 8 levels over the pixels both cover.

pyrender is not packaged for Debian: the comparison runs where FACET_PYRENDER_SOURCE names a checkout of
github.com/mmatl/pyrender and Debian's python3-opengl, -pyglet, -scipy, -networkx, -imageio, -freetype and -pil
are installed (scripts/pyrender_compare.sh installs them and runs it), and is skipped, saying why, elsewhere.
"""
import os
import subprocess
import sys

import numpy as np
import pytest

SUPPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "support")
sys.path.insert(0, SUPPORT)
import pyrender_scenes  # noqa: E402

import facet  # noqa: E402

SOURCE = os.environ.get("FACET_PYRENDER_SOURCE", "")
MEAN_LEVELS = 8.0  # mean absolute difference (0-255, over the channels) where both draw a surface
# The pixels each draws: the same silhouettes up to the edges' pixels. pyrender's lie about a third of a pixel
# higher than facet's (facet puts a centred sphere's centroid at the image's centre), which costs small shapes a
# few percent of their pixels.
COVERAGE_IOU = 0.95


def _require_pyrender():
    if not SOURCE or not os.path.isdir(os.path.join(SOURCE, "pyrender")):
        pytest.skip("pyrender's source is not here: set FACET_PYRENDER_SOURCE to a checkout of "
                    "github.com/mmatl/pyrender (Debian does not package it; scripts/pyrender_compare.sh runs this)")


def _pyrender_images(tmp_path):
    _require_pyrender()
    out = tmp_path / "pyrender.npz"
    env = dict(os.environ, PYOPENGL_PLATFORM="egl",
               PYTHONPATH=os.pathsep.join([SUPPORT, SOURCE, os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, os.path.join(SUPPORT, "render_with.py"), "pyrender", str(out)], env=env,
                         capture_output=True, text=True, timeout=600)
    if run.returncode != 0:
        pytest.skip(f"pyrender does not run here (its packages or EGL): {run.stderr.strip().splitlines()[-1:]}")
    return np.load(out)


def _box5(image):
    """The image's mean over each 5 x 5 window."""
    return np.lib.stride_tricks.sliding_window_view(image.astype(float), (5, 5), axis=(0, 1)).mean(axis=(-1, -2))


def test_pyrender_and_facet_draw_the_same_scenes_alike(tmp_path):
    theirs = _pyrender_images(tmp_path)
    ours = pyrender_scenes.render_all(facet)
    report = []
    for name, (color, depth) in ours.items():
        their_color, their_depth = theirs[f"{name}_color"], theirs[f"{name}_depth"]
        assert color.shape == their_color.shape and depth.shape == their_depth.shape
        if name == "points":
            # Which pixel a 1-pixel point lands in turns on the sample positions (pyrender's depth is its first
            # sample's, a third of a pixel off the centre), so the cloud's images are compared filtered over 5 x 5
            # pixels, and by all the light they hold.
            near = _box5((depth > 0) | (their_depth > 0)) > 0
            mean = np.abs(_box5(color) - _box5(their_color))[near].mean()
            light = color.sum() / their_color.sum()
            report.append(f"{name}: mean {mean:.2f} over 5 x 5 pixels, light ratio {light:.4f}")
            assert mean <= MEAN_LEVELS / 4 and abs(light - 1.0) < 0.02, "; ".join(report)
            continue
        both, either = (depth > 0) & (their_depth > 0), (depth > 0) | (their_depth > 0)
        iou = both.sum() / max(either.sum(), 1)
        mean = np.abs(color.astype(int) - their_color.astype(int))[both].mean()
        report.append(f"{name}: mean {mean:.1f}, coverage IoU {iou:.4f}")
        assert iou >= COVERAGE_IOU and mean <= MEAN_LEVELS, "; ".join(report)
    print("\n".join(report))


def _run_example(module, out, extra_path):
    env = dict(os.environ, PYOPENGL_PLATFORM="egl",
               PYTHONPATH=os.pathsep.join([SUPPORT, extra_path, os.environ.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, os.path.join(SUPPORT, "run_example.py"), module,
                           os.path.join(SOURCE, "examples"), str(out)], env=env, capture_output=True, text=True,
                          timeout=600)


def test_pyrenders_example_draws_what_pyrender_draws(tmp_path):
    """examples/example.py, unchanged but for its viewer and pyglet lines: the textured, vertex- and face-coloured
    meshes under a directional and a spot light, and the segmentation of its mesh nodes."""
    _require_pyrender()
    theirs_run = _run_example("pyrender", tmp_path / "theirs.npz", SOURCE)
    if theirs_run.returncode != 0:
        pytest.skip(f"pyrender's example does not run here: {theirs_run.stderr.strip().splitlines()[-1:]}")
    ours_run = _run_example("facet", tmp_path / "ours.npz", "")
    assert ours_run.returncode == 0, ours_run.stderr
    theirs, ours = np.load(tmp_path / "theirs.npz"), np.load(tmp_path / "ours.npz")
    both = (ours["depth"] > 0) & (theirs["depth"] > 0)
    assert both.sum() / ((ours["depth"] > 0) | (theirs["depth"] > 0)).sum() >= COVERAGE_IOU
    assert np.abs(ours["color"].astype(int) - theirs["color"].astype(int))[both].mean() <= MEAN_LEVELS
    # The segmentation numbers the nodes in the order of a set, so compare the regions, not their values: each of
    # facet's grey levels covers pixels of one of pyrender's.
    ours_seg, theirs_seg = ours["seg"][..., 0][both], theirs["seg"][..., 0][both]
    agreeing = sum(np.bincount(theirs_seg[ours_seg == level]).max() for level in np.unique(ours_seg))
    assert agreeing / both.sum() >= COVERAGE_IOU
