"""A small stand-in for the parts of trimesh that pyrender and its tests use, built on numpy and PIL only."""
from . import bounds, creation, exchange, transformations, util, visual
from .base import Trimesh
from .exchange.load import load, load_mesh
from .scene import Scene, SceneGraph

__version__ = "0.0.0+standin"

__all__ = ["Trimesh", "Scene", "SceneGraph", "load", "load_mesh", "bounds", "creation", "exchange",
           "transformations", "util", "visual"]
