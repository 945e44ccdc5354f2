"""renderer.py - OffscreenRenderer and facet.render: frames of a scene or a model file as numpy arrays."""
import enum
import json
import os

import numpy as np

from . import _facet
from .light import DirectionalLight, light_tuple
from .scene import DEFAULT_MAX_POINTS, DEFAULT_MAX_TEXTURE_SIZE, DEFAULT_MAX_TRIANGLES


class RenderFlags(enum.IntFlag):
    """What OffscreenRenderer.render draws and returns; pyrender's values, combinable with |."""

    NONE = 0
    DEPTH_ONLY = 1  # return the depth alone
    ALL_WIREFRAME = 8  # draw every mesh as lines
    SHADOWS_DIRECTIONAL = 32  # directional lights cast shadows
    SHADOWS_POINT = 64  # accepted; point lights cast no shadows in facet
    SHADOWS_SPOT = 128  # spot lights cast shadows
    SHADOWS_ALL = 32 | 64 | 128
    SKIP_CULL_FACES = 1024  # draw back faces too (otherwise those of single-sided materials are culled, as in pyrender)
    RGBA = 2048  # colour H x W x 4, alpha 0 where the background shows through a transparent bg_color
    FLAT = 4096  # one lit colour per face
    SEG = 8192  # return the id buffer (H x W x 2 uint32: node id, face id) in place of colour


BUFFERS = ("color", "depth", "normal", "ids", "mask")

# The headlight of a scene without lights: from the camera, above left, as `facet render` lights models; its pose
# relative to the camera's turns its +z axis towards that direction.
_HEADLIGHT = DirectionalLight()
_HEADLIGHT_POSE = np.eye(4)
_HEADLIGHT_POSE[:3, 2] = np.array(_facet.HEADLIGHT_FROM_CAMERA)


class OffscreenRenderer:
    """Renders scenes at width x height on the CPU: no GPU, display or GL context.

    threads: the renderer's worker threads (0: one per hardware thread). Each renderer renders one frame at a
    time; renderers in different Python threads render in parallel (the GIL is released while drawing).
    samples: multisample anti-aliasing, 1, 2, 4 or 8 samples per pixel (4 as pyrender draws); depth, ids and the
    mask are taken at each pixel's centre, never blended.
    point_size: the side in pixels of the square each point of a point cloud (Mesh.from_points) covers.
    """

    def __init__(self, viewport_width, viewport_height, point_size=1.0, threads=0, samples=4):
        if samples not in (1, 2, 4, 8) or isinstance(samples, bool):
            raise ValueError(f"samples: expected 1, 2, 4 or 8, got {samples!r}")
        if not isinstance(threads, int) or threads < 0:
            raise ValueError(f"threads: expected 0 or more, got {threads!r}")
        self.point_size = point_size
        self._threads = threads
        self._core = _facet.RendererCore(int(viewport_width), int(viewport_height), threads, int(samples))

    @property
    def viewport_width(self):
        return self._core.width

    @property
    def viewport_height(self):
        return self._core.height

    def render(self, scene, flags=RenderFlags.NONE):
        """(color, depth) as pyrender returns them: color H x W x 3 uint8 (x 4 with RenderFlags.RGBA), depth H x W
        float32, linear eye-space depth, 0 where nothing is drawn. DEPTH_ONLY returns the depth alone; SEG returns
        (ids, depth)."""
        flags = RenderFlags(flags)
        if flags & RenderFlags.DEPTH_ONLY:
            return self.render_buffers(scene, ["depth"], flags)["depth"]
        first = "ids" if flags & RenderFlags.SEG else "color"
        out = self.render_buffers(scene, [first, "depth"], flags)
        return out[first], out["depth"]

    def render_buffers(self, scene, buffers=("color", "depth"), flags=RenderFlags.NONE):
        """A dict of the buffers named, all from one frame: "color" (H x W x 3 or 4 uint8), "depth" (H x W
        float32), "normal" (H x W x 3 float32, camera-space unit normals in OpenGL axes, 0 where empty), "ids"
        (H x W x 2 uint32: the node id and the face id in its mesh, 0xFFFFFFFF where empty) and "mask" (H x W
        uint8, 255 where a surface is drawn)."""
        flags = RenderFlags(flags)
        buffers = list(buffers)
        for name in buffers:
            if name not in BUFFERS:
                raise ValueError(f"buffers: unknown buffer {name!r} (one of {', '.join(BUFFERS)})")
        view = self._view(scene)
        casting = {"directional": bool(flags & RenderFlags.SHADOWS_DIRECTIONAL),
                   "spot": bool(flags & RenderFlags.SHADOWS_SPOT), "point": False}
        lights = [light_tuple(node.light, node.pose, casting[node.light.kind]) for node in scene.light_nodes]
        if not lights:
            lights.append(light_tuple(_HEADLIGHT, view["pose"] @ _HEADLIGHT_POSE))
        shading = "flat" if flags & RenderFlags.FLAT else "automatic"
        return self._core.render(scene._core, view["view"], view["projection"], view["near"], view["far"], shading,
                                 not flags & RenderFlags.SKIP_CULL_FACES, bool(flags & RenderFlags.ALL_WIREFRAME),
                                 lights, scene.ambient_light, scene.bg_color, bool(flags & RenderFlags.RGBA),
                                 float(self.point_size), buffers)

    def camera_json(self, scene):
        """The main camera as `facet render --output-camera` writes it: width, height, near, far, projection,
        K (OpenCV intrinsics in pixels; None for parallel projections), world_from_camera (OpenGL axes),
        camera_from_world (OpenCV axes) and clip_from_view, matrices as lists of rows."""
        view = self._view(scene)
        return json.loads(self._core.camera_json(view["view"], view["projection"], view["near"], view["far"]))

    def delete(self):
        """Kept for pyrender's code: nothing needs freeing by hand."""

    def _view(self, scene):
        node = scene.main_camera_node
        if node is None:
            raise ValueError("the scene has no camera: add one with scene.add(camera, pose=...)")
        camera, pose = node.camera, node.pose
        far = camera.zfar
        if far is None:  # just beyond the farthest corner of the scene's box
            far = 100.0
            box = scene.bounds
            if box is not None:
                corners = np.array([[box[i, 0], box[j, 1], box[k, 2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
                far = max(float(np.linalg.norm(corners - pose[:3, 3], axis=1).max()) * 1.01, 2.0 * camera.znear)
        projection = camera.get_projection_matrix(self.viewport_width, self.viewport_height, zfar=far)
        return {"pose": pose, "view": np.linalg.inv(pose), "projection": projection, "near": camera.znear,
                "far": far}


def render(model, width=640, height=480, buffers=("color", "depth"), shading="automatic", azimuth=0.0,
           elevation=0.0, projection="perspective", up="+Y", camera_index=None, background=None, rgba=False,
           threads=0, samples=4, *, allow_external_files=False, max_triangles=DEFAULT_MAX_TRIANGLES,
           max_points=DEFAULT_MAX_POINTS, max_texture_size=DEFAULT_MAX_TEXTURE_SIZE, eye_dome_lighting=None,
           color_map="none"):
    """Renders a model file as `facet render` does (framed from the front right, above, lit by a headlight,
    anti-aliased with `samples` samples per pixel: 1, 2, 4 or 8) and returns a dict of the buffers named (see
    OffscreenRenderer.render_buffers, ids holding the file's node and face ids) plus "camera", the camera as
    render_buffers' camera_json gives it. The model is read within the limits Mesh.from_file takes.
    eye_dome_lighting: its strength, 0 (off) to 100, as `--eye-dome-lighting`; None: on for a point cloud with
    neither normals nor colours, off otherwise. color_map: "none" or "height", as `--color-map`."""
    for name in buffers:
        if name not in BUFFERS:
            raise ValueError(f"buffers: unknown buffer {name!r} (one of {', '.join(BUFFERS)})")
    return _facet.render_file(os.fspath(model), int(width), int(height), int(threads), int(samples), shading,
                              float(azimuth), float(elevation), projection, up, camera_index, background,
                              list(buffers), bool(rgba), bool(allow_external_files), max_triangles, max_points,
                              max_texture_size, None if eye_dome_lighting is None else float(eye_dome_lighting),
                              str(color_map))


__all__ = ["BUFFERS", "RenderFlags", "OffscreenRenderer", "render"]
