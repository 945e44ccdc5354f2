"""constants.py - pyrender's named values: render flags, glTF's enumerations and the default clipping planes."""
import enum

DEFAULT_Z_NEAR = 0.05  # metres, as pyrender's cameras default to
DEFAULT_Z_FAR = 100.0
DEFAULT_SCENE_SCALE = 2.0  # pyrender's scale for an empty scene
SHADOW_TEX_SZ = 2048  # the side of the shadow map pyrender's lights describe (facet's own maps are sized per frame)


class RenderFlags(enum.IntFlag):
    """What OffscreenRenderer.render draws and returns; pyrender's values, combinable with |. A value with a bit
    that is none of these raises ValueError."""

    NONE = 0
    DEPTH_ONLY = 1  # return the depth alone
    OFFSCREEN = 2  # kept: every facet render is offscreen
    FLIP_WIREFRAME = 4  # draw meshes whose material is wireframe as surfaces and the others as lines
    ALL_WIREFRAME = 8  # draw every mesh as lines
    ALL_SOLID = 16  # draw every mesh as a surface, wireframe materials too
    SHADOWS_DIRECTIONAL = 32  # directional lights cast shadows
    SHADOWS_POINT = 64  # accepted; point lights cast no shadows (nor do they in pyrender)
    SHADOWS_SPOT = 128  # spot lights cast shadows
    SHADOWS_ALL = 32 | 64 | 128
    VERTEX_NORMALS = 256  # draw each vertex's normal as a line
    FACE_NORMALS = 512  # draw each face's normal as a line
    SKIP_CULL_FACES = 1024  # draw back faces too (otherwise those of single-sided materials are culled)
    RGBA = 2048  # colour H x W x 4, alpha 0 where the background shows through a transparent bg_color
    FLAT = 4096  # unlit: base colour x vertex colour x texture, as pyrender's flat shader draws
    SEG = 8192  # colour each node from seg_node_map, unlit (render(scene, flags, seg_node_map))


def render_flags(value):
    """value as RenderFlags; ValueError for an integer with a bit pyrender does not define (IntFlag would keep it)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"flags: expected RenderFlags or an int, got {value!r}")
    unknown = int(value) & ~int(_ALL_FLAGS)
    if int(value) < 0 or unknown:
        raise ValueError(f"flags: {int(value)} has bits no RenderFlags value names ({unknown:#x})")
    return RenderFlags(int(value))


_ALL_FLAGS = RenderFlags(0)
for _flag in RenderFlags:
    _ALL_FLAGS |= _flag


class GLTF:
    """glTF's numbers for samplers' filters and wrapping and for primitives' modes, as pyrender names them."""

    NEAREST = 9728
    LINEAR = 9729
    NEAREST_MIPMAP_NEAREST = 9984
    LINEAR_MIPMAP_NEAREST = 9985
    NEAREST_MIPMAP_LINEAR = 9986
    LINEAR_MIPMAP_LINEAR = 9987
    CLAMP_TO_EDGE = 33071
    MIRRORED_REPEAT = 33648
    REPEAT = 10497
    POINTS = 0
    LINES = 1
    LINE_LOOP = 2
    LINE_STRIP = 3
    TRIANGLES = 4
    TRIANGLE_STRIP = 5
    TRIANGLE_FAN = 6


__all__ = ["DEFAULT_SCENE_SCALE", "DEFAULT_Z_FAR", "DEFAULT_Z_NEAR", "GLTF", "RenderFlags", "SHADOW_TEX_SZ"]
