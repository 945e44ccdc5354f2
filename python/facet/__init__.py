"""facet: a CPU rendering pipeline for Python, in pyrender's shapes; no GPU, display or GL context needed.

    import facet, numpy as np
    scene = facet.Scene.from_file("model.glb")
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=camera_pose)
    color, depth = facet.OffscreenRenderer(640, 480).render(scene)
    buffers = facet.render("model.glb", width=640, height=480, buffers=["color", "depth", "normal", "ids"])
"""
from ._facet import LoadError
from .light import DirectionalLight, PointLight, SpotLight
from .material import MetallicRoughnessMaterial
from .renderer import BUFFERS, OffscreenRenderer, RenderFlags, render
from .scene import IntrinsicsCamera, Mesh, Node, OrthographicCamera, PerspectiveCamera, Scene

__all__ = ["BUFFERS", "DirectionalLight", "IntrinsicsCamera", "LoadError", "Mesh", "MetallicRoughnessMaterial",
           "Node", "OffscreenRenderer", "OrthographicCamera", "PerspectiveCamera", "PointLight", "RenderFlags",
           "Scene", "SpotLight", "render"]
