"""renderer.py - OffscreenRenderer and facet.render: frames of a scene or a model file as numpy arrays."""
import json
import os
import warnings

import numpy as np

from . import _facet
from .constants import RenderFlags, render_flags
from .light import DirectionalLight, light_tuple
from .mesh import DEFAULT_MAX_POINTS, DEFAULT_MAX_TEXTURE_SIZE, DEFAULT_MAX_TRIANGLES


BUFFERS = ("color", "depth", "normal", "ids", "mask")  # what one frame gives; facet.render adds "motion"

# The headlight of a scene without lights: from the camera, above left, as `facet render` lights models; its pose
# relative to the camera's turns its +z axis towards that direction.
_HEADLIGHT = DirectionalLight()
_HEADLIGHT_POSE = np.eye(4)
_HEADLIGHT_POSE[:3, 2] = np.array(_facet.HEADLIGHT_FROM_CAMERA)


class OffscreenRenderer:
    """Renders scenes at viewport_width x viewport_height on the CPU: no GPU, display or GL context.

    point_size: the side in pixels of the square each point of a point cloud (Mesh.from_points) covers.
    threads: the renderer's worker threads (0: one per hardware thread). Each renderer renders one frame at a
    time; renderers in different Python threads render in parallel (the GIL is released while drawing).
    samples: multisample anti-aliasing, 1, 2, 4 or 8 samples per pixel (4 as pyrender draws); depth, ids and the
    mask are taken at each pixel's centre, never blended.
    """

    def __init__(self, viewport_width, viewport_height, point_size=1.0, threads=0, samples=4):
        if samples not in (1, 2, 4, 8) or isinstance(samples, bool):
            raise ValueError(f"samples: expected 1, 2, 4 or 8, got {samples!r}")
        if not isinstance(threads, int) or threads < 0:
            raise ValueError(f"threads: expected 0 or more, got {threads!r}")
        self.point_size = point_size
        self._threads, self._samples = threads, int(samples)
        self._core = _facet.RendererCore(int(viewport_width), int(viewport_height), threads, self._samples)

    @property
    def viewport_width(self):
        return self._core.width

    @viewport_width.setter
    def viewport_width(self, value):
        self._resize(value, self.viewport_height)

    @property
    def viewport_height(self):
        return self._core.height

    @viewport_height.setter
    def viewport_height(self, value):
        self._resize(self.viewport_width, value)

    def _resize(self, width, height):
        if (int(width), int(height)) != (self.viewport_width, self.viewport_height):
            self._core = _facet.RendererCore(int(width), int(height), self._threads, self._samples)

    @property
    def point_size(self):
        return self._point_size

    @point_size.setter
    def point_size(self, value):
        v = float(value)
        if not 0.0 < v < float("inf"):
            raise ValueError(f"point_size: must be positive and finite, got {value!r}")
        self._point_size = v

    def render(self, scene, flags=RenderFlags.NONE, seg_node_map=None):
        """(color, depth) as pyrender returns them: color H x W x 3 uint8 (x 4 with RenderFlags.RGBA), depth H x W
        float32, linear eye-space depth, 0 where nothing is drawn. DEPTH_ONLY returns the depth alone. SEG draws
        only the nodes seg_node_map maps to colours (0..255 RGB, or one grey value), each flat in its colour on
        black, without anti-aliasing."""
        flags = render_flags(flags)
        if flags & RenderFlags.DEPTH_ONLY:
            return self.render_buffers(scene, ["depth"], flags)["depth"]
        if flags & RenderFlags.SEG:
            return self._segmentation(scene, flags, seg_node_map or {})
        out = self.render_buffers(scene, ["color", "depth"], flags)
        return out["color"], out["depth"]

    def render_buffers(self, scene, buffers=("color", "depth"), flags=RenderFlags.NONE):
        """A dict of the buffers named, all from one frame: "color" (H x W x 3 or 4 uint8), "depth" (H x W
        float32), "normal" (H x W x 3 float32, camera-space unit normals in OpenGL axes, 0 where empty), "ids"
        (H x W x 2 uint32: the node id and the face id in its mesh, 0xFFFFFFFF where empty) and "mask" (H x W
        uint8, 255 where a surface is drawn)."""
        flags = render_flags(flags)
        buffers = list(buffers)
        for name in buffers:
            if name == "motion":
                raise ValueError("buffers: motion needs a model file's animation: facet.render gives it")
            if name not in BUFFERS:
                raise ValueError(f"buffers: unknown buffer {name!r} (one of {', '.join(BUFFERS)})")
        if flags & (RenderFlags.VERTEX_NORMALS | RenderFlags.FACE_NORMALS):
            warnings.warn("facet draws no normal lines: RenderFlags.VERTEX_NORMALS and FACE_NORMALS are ignored",
                          stacklevel=3)
        flat = bool(flags & RenderFlags.FLAT)
        return self._draw(scene, scene._core, scene._instances(flat=flat), flags, buffers, flat, scene.bg_color)

    def _draw(self, scene, core, instances, flags, buffers, unlit, background):
        view = self._view(scene)
        core.sync([(mesh, pose, node_id, _wireframe(flags, wire)) for mesh, pose, node_id, wire in instances])
        casting = {"directional": bool(flags & RenderFlags.SHADOWS_DIRECTIONAL),
                   "spot": bool(flags & RenderFlags.SHADOWS_SPOT), "point": False}
        lights = [light_tuple(light, pose, casting[light.kind]) for light, pose in scene._placed_lights()]
        if not lights:
            lights.append(light_tuple(_HEADLIGHT, view["pose"] @ _HEADLIGHT_POSE))
        return self._core.render(core, view["view"], view["projection"], view["near"], view["far"],
                                 "unlit" if unlit else "automatic", not flags & RenderFlags.SKIP_CULL_FACES, False,
                                 lights, scene.ambient_light, background, bool(flags & RenderFlags.RGBA),
                                 self.point_size, buffers)

    def _segmentation(self, scene, flags, seg_node_map):
        """pyrender's segmentation image: each mapped node's surfaces in its colour, the rest left out."""
        colors = {}
        for node, color in seg_node_map.items():
            c = np.asarray(color, dtype=np.float64).reshape(-1)
            c = np.repeat(c, 3) if c.size == 1 else c
            if c.size != 3 or not np.all((c >= 0.0) & (c <= 255.0)):
                raise ValueError(f"seg_node_map: expected 0..255 RGB colours or grey values, got {color!r}")
            colors[node] = np.rint(c).astype(np.uint8)
        out = self._draw(scene, scene._seg_core, scene._instances(only=colors), flags & ~RenderFlags.FLAT,
                         ["ids", "depth"], True, np.array([0.0, 0.0, 0.0, 1.0]))
        ids = out["ids"][..., 0]
        table_ids = np.array([n.id for n in colors] + [0xFFFFFFFF], dtype=np.uint32)
        table = np.vstack([np.array(list(colors.values()), dtype=np.uint8).reshape(-1, 3), np.zeros((1, 3), np.uint8)])
        order = np.argsort(table_ids)
        where = np.searchsorted(table_ids[order], ids)
        color = table[order][np.minimum(where, len(order) - 1)]
        if flags & RenderFlags.RGBA:
            color = np.concatenate([color, np.full(color.shape[:2] + (1,), 255, np.uint8)], axis=2)
        return color, out["depth"]

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
        camera, pose = node.camera, scene.get_pose(node)
        if not camera.znear > 0.0:
            raise ValueError("the camera's znear is 0: facet needs a near plane in front of the camera")
        far = camera.zfar
        if far is None:  # just beyond the farthest corner of the scene's box
            far = 100.0
            box = scene.bounds
            if np.any(box != 0.0):
                corners = np.array([[box[i, 0], box[j, 1], box[k, 2]] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
                far = max(float(np.linalg.norm(corners - pose[:3, 3], axis=1).max()) * 1.01, 2.0 * camera.znear)
        projection = camera._projection(self.viewport_width, self.viewport_height, far)
        return {"pose": pose, "view": np.linalg.inv(pose), "projection": projection, "near": camera.znear,
                "far": far}


def _wireframe(flags, material_wireframe):
    """Whether a mesh is drawn as lines: its material's wireframe, flipped by FLIP_WIREFRAME, overridden by
    ALL_WIREFRAME and then ALL_SOLID."""
    if flags & RenderFlags.ALL_WIREFRAME:
        return True
    if flags & RenderFlags.ALL_SOLID:
        return False
    return material_wireframe != bool(flags & RenderFlags.FLIP_WIREFRAME)


def render(model, width=640, height=480, buffers=("color", "depth"), shading="automatic", azimuth=0.0,
           elevation=0.0, projection="perspective", up="+Y", camera_index=None, background=None, rgba=False,
           threads=0, samples=4, *, allow_external_files=False, max_triangles=DEFAULT_MAX_TRIANGLES,
           max_points=DEFAULT_MAX_POINTS, max_texture_size=DEFAULT_MAX_TEXTURE_SIZE, eye_dome_lighting=None,
           color_map="none", animation=None, time=None, fps=30.0, motion_time=None, motion_azimuth=0.0,
           motion_elevation=0.0):
    """Renders a model file as `facet render` does (framed from the front right, above, lit by a headlight,
    anti-aliased with `samples` samples per pixel: 1, 2, 4 or 8) and returns a dict of the buffers named (see
    OffscreenRenderer.render_buffers, ids holding the file's node and face ids) plus "camera", the camera as
    render_buffers' camera_json gives it. The model is read within the limits Mesh.from_file takes.
    eye_dome_lighting: its strength, 0 (off) to 100, as `--eye-dome-lighting`; None: on for a point cloud with
    neither normals nor colours, off otherwise. color_map: "none", "height" or "intensity", as `--color-map`.
    animation, time: the model's animation (a glTF file's, by name or index; None: the first) posed `time` seconds
    in, as `--animation` and `--time`; skins and morph targets are drawn at rest without either. The "motion"
    buffer (H x W x 2 float32) is each pixel's motion on the image, in pixels (+x right, +y down), from `time` to
    1/fps later, as `--output-motion` writes it; or to `motion_time`, and through the camera turned by
    `motion_azimuth` and lifted by `motion_elevation` degrees: motion between two times, two camera poses or both."""
    for name in buffers:
        if name not in BUFFERS + ("motion",):
            raise ValueError(f"buffers: unknown buffer {name!r} (one of {', '.join(BUFFERS)}, motion)")
    return _facet.render_file(os.fspath(model), int(width), int(height), int(threads), int(samples), shading,
                              float(azimuth), float(elevation), projection, up, camera_index, background,
                              list(buffers), bool(rgba), bool(allow_external_files), max_triangles, max_points,
                              max_texture_size, None if eye_dome_lighting is None else float(eye_dome_lighting),
                              str(color_map), None if animation is None else str(animation),
                              None if time is None else float(time), float(fps),
                              None if motion_time is None else float(motion_time), float(motion_azimuth),
                              float(motion_elevation))


__all__ = ["BUFFERS", "RenderFlags", "OffscreenRenderer", "render"]
