"""scene.py - meshes, cameras and the scene graph that places them and the lights, in pyrender's shapes."""
import math
import warnings

import numpy as np

from . import _facet
from .light import DirectionalLight, PointLight, SpotLight, _color
from .material import MetallicRoughnessMaterial


def _pose(pose, name="pose"):
    """A 4x4 float64 copy of pose (identity for None); raises ValueError for anything else."""
    if pose is None:
        return np.eye(4)
    m = np.array(pose, dtype=np.float64)
    if m.shape != (4, 4):
        raise ValueError(f"{name}: expected a 4x4 matrix, got shape {m.shape}")
    if not np.all(np.isfinite(m)):
        raise ValueError(f"{name}: holds a non-finite value")
    return m


# The limits model files are read within by default, as `facet render` reads them (LoadOptions in the C++ library's
# model_io.hpp): files a model names are read only from inside its folder tree, at most 100 million triangles are
# placed, and textures up to 16384 texels a side are decoded.
DEFAULT_MAX_TRIANGLES = _facet.DEFAULT_MAX_TRIANGLES
DEFAULT_MAX_POINTS = _facet.DEFAULT_MAX_POINTS
DEFAULT_MAX_TEXTURE_SIZE = _facet.MAX_TEXTURE_SIZE


class Mesh:
    """A triangle mesh: positions N x 3, faces F x 3, and optional per-vertex normals, uvs and colours, a texture
    and a MetallicRoughnessMaterial.

    Any float and integer dtypes and memory orders are accepted; faces must be integers. Colours are floats in 0..1
    or uint8, N x 3 or N x 4, as displayed (sRGB-encoded), multiplying the material's base colour. A texture is an
    image H x W (x 3 or 4), top row first, uint8 or floats in 0..1, drawn with the uvs (v = 0 at the image's bottom
    row, as in OpenGL and pyrender); a material's own baseColorTexture replaces it. Without a material the mesh is
    white, a dielectric of roughness 0.5, single-sided. Bad arrays and values raise ValueError.
    """

    material = None  # the MetallicRoughnessMaterial it was made with; None for meshes from files

    def __init__(self, positions, faces, normals=None, uvs=None, colors=None, texture=None, material=None):
        description = _material_description(material)
        self.material = material
        self._core = _facet.MeshCore(positions, faces, normals, uvs, colors, texture, description)

    @classmethod
    def from_file(cls, path, *, allow_external_files=False, max_triangles=DEFAULT_MAX_TRIANGLES,
                  max_points=DEFAULT_MAX_POINTS, max_texture_size=DEFAULT_MAX_TEXTURE_SIZE):
        """The whole model file as one mesh in world space (every format `facet render` reads).

        Model files are untrusted input, read within limits: the files a model names (materials, textures, buffers)
        are read only from inside its folder tree unless allow_external_files; a model placing more than
        max_triangles triangles, or more than max_points points and Gaussian splats together, is refused; a
        texture wider or taller than max_texture_size is not decoded (its
        material is drawn untextured, with a warning).

        Raises FileNotFoundError for a missing file and facet.LoadError (an OSError and a ValueError) for one that
        cannot be read, naming the file and the problem; ValueError for a limit out of range.
        """
        mesh = cls.__new__(cls)
        mesh._core = _facet.MeshCore.from_file(str(path), bool(allow_external_files), max_triangles, max_points,
                                               max_texture_size)
        return mesh

    @classmethod
    def from_points(cls, points, colors=None, normals=None, material=None):
        """A point cloud: positions N x 3, each drawn as a point of the renderer's point_size pixels, with optional
        per-point colours (as for a mesh) and normals. With normals the points are lit like a surface; without, they
        are drawn in their colours (or the material's base colour), unlit."""
        mesh = cls.__new__(cls)
        mesh.material = material
        mesh._core = _facet.MeshCore(points, None, normals, None, colors, None, _material_description(material))
        return mesh

    @classmethod
    def from_trimesh(cls, mesh, material=None, smooth=True):
        """From a trimesh.Trimesh: its vertices, faces and vertex normals, with `material`, or else with its vertex
        colours (as pyrender takes them). smooth=False draws each face flat, with its face normal."""
        colors = None
        visual = getattr(mesh, "visual", None)
        if material is None and visual is not None and getattr(visual, "kind", None) == "vertex":
            colors = np.asarray(visual.vertex_colors)
        vertices, faces = np.asarray(mesh.vertices), np.asarray(mesh.faces)
        if smooth:
            return cls(vertices, faces, normals=np.asarray(mesh.vertex_normals), colors=colors, material=material)
        # Three vertices of its own per face, each with the face's normal, as pyrender splits them.
        corners = faces.reshape(-1)
        normals = np.repeat(np.asarray(mesh.face_normals), 3, axis=0)
        return cls(vertices[corners], np.arange(corners.size).reshape(-1, 3), normals=normals,
                   colors=None if colors is None else colors[corners], material=material)

    @property
    def bounds(self):
        """2 x 3: the minimum and maximum corner of the positions."""
        return self._core.bounds

    @property
    def centroid(self):
        return self.bounds.mean(axis=0)

    @property
    def vertex_count(self):
        return self._core.vertex_count

    @property
    def triangle_count(self):
        return self._core.triangle_count

    @property
    def point_count(self):
        """The points it draws (a point cloud's positions); 0 for a triangle mesh."""
        return self._core.point_count


class PerspectiveCamera:
    """A pinhole camera with a vertical field of view (radians); zfar None: just beyond the scene."""

    def __init__(self, yfov, znear=0.05, zfar=None, aspectRatio=None, name=None):
        if not 0.0 < yfov < math.pi:
            raise ValueError(f"yfov: must lie in (0, pi), got {yfov}")
        _check_planes(znear, zfar)
        if aspectRatio is not None and not aspectRatio > 0.0:
            raise ValueError(f"aspectRatio: must be positive, got {aspectRatio}")
        self.yfov, self.znear, self.zfar, self.aspectRatio, self.name = yfov, znear, zfar, aspectRatio, name

    def get_projection_matrix(self, width, height, zfar=None):
        far = self.zfar if self.zfar is not None else zfar
        aspect = self.aspectRatio if self.aspectRatio is not None else width / height
        t = math.tan(self.yfov / 2.0)
        p = np.zeros((4, 4))
        p[0, 0] = 1.0 / (aspect * t)
        p[1, 1] = 1.0 / t
        _depth_rows(p, self.znear, far)
        return p


class IntrinsicsCamera:
    """A pinhole camera given in pixels, in OpenCV's convention: a point at camera coordinates (X, Y, Z), x right,
    y down, z forward, lands at u = fx X / Z + cx, v = fy Y / Z + cy, where pixel (0, 0)'s centre is u = v = 0.
    Its pose is camera-to-world in OpenGL axes, like every camera's."""

    def __init__(self, fx, fy, cx, cy, znear=0.05, zfar=100.0, name=None):
        if not (fx > 0.0 and fy > 0.0):
            raise ValueError(f"fx, fy: must be positive, got {fx}, {fy}")
        if not (math.isfinite(cx) and math.isfinite(cy)):
            raise ValueError("cx, cy: must be finite")
        _check_planes(znear, zfar)
        self.fx, self.fy, self.cx, self.cy, self.znear, self.zfar, self.name = fx, fy, cx, cy, znear, zfar, name

    def get_projection_matrix(self, width, height, zfar=None):
        far = self.zfar if self.zfar is not None else zfar
        p = np.zeros((4, 4))
        p[0, 0] = 2.0 * self.fx / width
        p[0, 2] = 1.0 - 2.0 * (self.cx + 0.5) / width
        p[1, 1] = 2.0 * self.fy / height
        p[1, 2] = 2.0 * (self.cy + 0.5) / height - 1.0
        _depth_rows(p, self.znear, far)
        return p


class OrthographicCamera:
    """A parallel projection showing xmag and ymag either side of the view's centre."""

    def __init__(self, xmag, ymag, znear=0.05, zfar=100.0, name=None):
        if not (xmag > 0.0 and ymag > 0.0):
            raise ValueError(f"xmag, ymag: must be positive, got {xmag}, {ymag}")
        if not (math.isfinite(znear) and zfar is not None and math.isfinite(zfar) and zfar > znear):
            raise ValueError(f"znear, zfar: need finite znear < zfar, got {znear}, {zfar}")
        self.xmag, self.ymag, self.znear, self.zfar, self.name = xmag, ymag, znear, zfar, name

    def get_projection_matrix(self, width=None, height=None, zfar=None):
        n, f = self.znear, self.zfar
        p = np.zeros((4, 4))
        p[0, 0] = 1.0 / self.xmag
        p[1, 1] = 1.0 / self.ymag
        p[2, 2] = 2.0 / (n - f)
        p[2, 3] = (f + n) / (n - f)
        p[3, 3] = 1.0
        return p


def _check_planes(znear, zfar):
    if not (math.isfinite(znear) and znear > 0.0):
        raise ValueError(f"znear: must be positive, got {znear}")
    if zfar is not None and not (math.isfinite(zfar) and zfar > znear):
        raise ValueError(f"zfar: must lie beyond znear, got {zfar}")


def _depth_rows(p, n, f):
    p[2, 2] = -(f + n) / (f - n)
    p[2, 3] = -2.0 * f * n / (f - n)
    p[3, 2] = -1.0


_LIGHTS = (DirectionalLight, PointLight, SpotLight)


def _material_description(material):
    """A mesh's material as the compiled module takes it; warns where facet draws it differently from pyrender."""
    if material is None:
        return None
    if not isinstance(material, MetallicRoughnessMaterial):
        raise ValueError(f"material: expected a facet.MetallicRoughnessMaterial, got {type(material).__name__}")
    description = material._core_dict()
    if material.wireframe:
        warnings.warn("facet draws a material's wireframe as a surface; RenderFlags.ALL_WIREFRAME draws every mesh "
                      "as lines", stacklevel=3)
    return description


class Node:
    """A mesh, camera or light placed in a scene; `id` is the node's number in the id buffer."""

    def __init__(self, obj, pose, node_id, name=None):
        self.obj, self.pose, self.id, self.name = obj, pose, node_id, name

    @property
    def mesh(self):
        return self.obj if isinstance(self.obj, Mesh) else None

    @property
    def camera(self):
        return self.obj if isinstance(self.obj, (PerspectiveCamera, IntrinsicsCamera, OrthographicCamera)) else None

    @property
    def light(self):
        return self.obj if isinstance(self.obj, _LIGHTS) else None


class Scene:
    """Meshes, cameras and lights, each placed by a 4x4 pose (object-to-world; camera-to-world in OpenGL axes).

    With no light, a scene is lit by a headlight from the camera, above left, as `facet render` lights models.
    """

    def __init__(self, nodes=None, bg_color=None, ambient_light=None, name=None):
        self.bg_color = _color(bg_color, (0.0, 0.0, 0.0, 0.0), "bg_color")
        self.ambient_light = _color(ambient_light, (0.15, 0.15, 0.15), "ambient_light")[:3]
        self.name = name
        self._core = _facet.SceneCore()
        self._nodes = []
        self._mesh_nodes = []  # in the order of the core scene's instances
        self._next_id = 0
        self.main_camera_node = None
        for node in nodes or []:
            self.add_node(node)

    @classmethod
    def from_file(cls, path, bg_color=None, ambient_light=None, *, allow_external_files=False,
                  max_triangles=DEFAULT_MAX_TRIANGLES, max_points=DEFAULT_MAX_POINTS,
                  max_texture_size=DEFAULT_MAX_TEXTURE_SIZE):
        """Every mesh of a model file, placed by the file's nodes (node ids as the file numbers them), and the
        file's cameras. Reads within the limits Mesh.from_file takes, and raises as it does."""
        meshes, instances, cameras = _facet.read_model(str(path), bool(allow_external_files), max_triangles,
                                                       max_points, max_texture_size)
        scene = cls(bg_color=bg_color, ambient_light=ambient_light)
        wrapped = []
        for core in meshes:
            mesh = Mesh.__new__(Mesh)
            mesh._core = core
            wrapped.append(mesh)
        for mesh_index, pose, node_id in instances:
            scene.add(wrapped[mesh_index], pose=pose, node_id=node_id)
        for c in cameras:
            if c["perspective"]:
                camera = PerspectiveCamera(c["yfov"], znear=c["znear"], zfar=c["zfar"], name=c["name"])
            else:
                camera = OrthographicCamera(c["xmag"], c["ymag"], znear=c["znear"], zfar=c["zfar"], name=c["name"])
            scene.add(camera, pose=c["pose"])
        return scene

    @property
    def nodes(self):
        return list(self._nodes)

    @property
    def mesh_nodes(self):
        return [n for n in self._nodes if n.mesh is not None]

    @property
    def camera_nodes(self):
        return [n for n in self._nodes if n.camera is not None]

    @property
    def light_nodes(self):
        return [n for n in self._nodes if n.light is not None]

    @property
    def bounds(self):
        """2 x 3: the corners of the box around every placed mesh, or None when there is none."""
        return self._core.bounds()

    def add(self, obj, pose=None, name=None, node_id=None):
        """Places a Mesh, camera or light and returns its Node; the first camera becomes the main camera."""
        if node_id is None:
            node_id = self._next_id
        if not isinstance(node_id, int) or not 0 <= node_id < 0xFFFFFFFF:
            raise ValueError(f"node_id: expected an integer in 0..2^32-2, got {node_id!r}")
        node = Node(obj, _pose(pose), node_id, name)
        return self.add_node(node)

    def add_node(self, node):
        if not isinstance(node.obj, (Mesh, PerspectiveCamera, IntrinsicsCamera, OrthographicCamera) + _LIGHTS):
            raise ValueError(f"cannot add a {type(node.obj).__name__} to a scene")
        if node in self._nodes:
            raise ValueError("the node is already in the scene")
        node.pose = _pose(node.pose)
        if node.mesh is not None:
            self._core.add(node.mesh._core, node.pose, node.id)
            self._mesh_nodes.append(node)
        if node.camera is not None and self.main_camera_node is None:
            self.main_camera_node = node
        self._nodes.append(node)
        self._next_id = max(self._next_id, node.id + 1)
        return node

    def has_node(self, node):
        return node in self._nodes

    def set_pose(self, node, pose):
        if node not in self._nodes:
            raise ValueError("the node is not in this scene")
        node.pose = _pose(pose)
        if node.mesh is not None:
            self._core.set_pose(self._mesh_nodes.index(node), node.pose)

    def get_pose(self, node):
        return node.pose.copy()

    def remove_node(self, node):
        if node not in self._nodes:
            raise ValueError("the node is not in this scene")
        if node.mesh is not None:
            index = self._mesh_nodes.index(node)
            self._core.remove(index)
            del self._mesh_nodes[index]
        self._nodes.remove(node)
        if node is self.main_camera_node:
            cameras = self.camera_nodes
            self.main_camera_node = cameras[0] if cameras else None
