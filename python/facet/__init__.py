"""facet: a CPU rendering pipeline for Python, in pyrender's shapes; no GPU, display or GL context needed.

    import facet, numpy as np
    scene = facet.Scene.from_file("model.glb")
    scene.add(facet.PerspectiveCamera(yfov=0.8), pose=camera_pose)
    color, depth = facet.OffscreenRenderer(640, 480).render(scene)
    buffers = facet.render("model.glb", width=640, height=480, buffers=["color", "depth", "normal", "ids"])
"""
from ._facet import LoadError, __version__
from .camera import Camera, IntrinsicsCamera, OrthographicCamera, PerspectiveCamera
from .constants import GLTF, RenderFlags
from .light import DirectionalLight, Light, PointLight, SpotLight
from .material import Material, MetallicRoughnessMaterial
from .mesh import Mesh
from .node import Node
from .primitive import Primitive
from .renderer import BUFFERS, OffscreenRenderer, render
from .scene import Scene
from .texture import Sampler, Texture

__all__ = ["BUFFERS", "Camera", "DirectionalLight", "GLTF", "IntrinsicsCamera", "Light", "LoadError", "Material",
           "Mesh", "MetallicRoughnessMaterial", "Node", "OffscreenRenderer", "OrthographicCamera",
           "PerspectiveCamera", "PointLight", "Primitive", "RenderFlags", "Sampler", "Scene", "SpotLight", "Texture",
           "__version__", "render"]
