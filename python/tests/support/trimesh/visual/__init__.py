"""How a mesh looks: ColorVisuals (vertex or face colours) and TextureVisuals (uvs and a material)."""
from . import color, material, texture
from .color import DEFAULT_COLOR, ColorVisuals, to_rgba
from .texture import TextureVisuals

__all__ = ["ColorVisuals", "TextureVisuals", "DEFAULT_COLOR", "to_rgba", "color", "material", "texture"]
