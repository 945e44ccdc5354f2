"""scene.py - pyrender's Scene: a tree of nodes placing meshes, cameras and lights, and how it is drawn."""
import numpy as np

from ._shared import BoxMeasures, color_vector, name_property
from . import _facet
from .camera import Camera, OrthographicCamera, PerspectiveCamera
from .light import DirectionalLight, Light, PointLight, SpotLight
from .mesh import DEFAULT_MAX_POINTS, DEFAULT_MAX_TEXTURE_SIZE, DEFAULT_MAX_TRIANGLES, Mesh
from .node import Node
from .primitive import CorePrimitive, posed_bounds


class Scene(BoxMeasures):
    """Nodes in a tree, each placing a mesh, camera or light by its matrix relative to its parent (cameras'
    poses are camera-to-world in OpenGL axes). bg_color: RGBA, white by default; ambient_light: linear RGB, none by
    default, as in pyrender. A scene without lights is lit by a headlight from the camera, above left, as
    `facet render` lights models (pyrender draws it black but for the ambient light)."""

    def __init__(self, nodes=None, bg_color=None, ambient_light=None, name=None):
        self.name, self.bg_color, self.ambient_light = name, bg_color, ambient_light
        self.clear()
        self._next_id = 0
        self._core = _facet.SceneCore()
        # Scene.from_file's: the file's motion (None without) and, per instance it placed, its node and the
        # primitive of its own mesh when a skin or morph targets deform it.
        self._motion, self._placed = None, []
        # What RenderFlags.SEG draws: the mapped nodes alone, prepared apart from the frames of the whole scene.
        self._seg_core = _facet.SceneCore()
        nodes = list(nodes or [])
        parent = {}
        for node in nodes:
            for child in node.children:
                if parent.get(child) is not None:
                    raise ValueError("Scene: a node is the child of more than one node")
                parent[child] = node
        for node in nodes:
            if parent.get(node) is None:
                self.add_node(node)

    name = name_property()

    @property
    def bg_color(self):
        return self._bg_color

    @bg_color.setter
    def bg_color(self, value):
        self._bg_color = np.ones(4) if value is None else color_vector(value, 4, "bg_color")

    @property
    def ambient_light(self):
        return self._ambient_light

    @ambient_light.setter
    def ambient_light(self, value):
        self._ambient_light = np.zeros(3) if value is None else color_vector(value, 3, "ambient_light")

    def clear(self):
        """Removes every node."""
        self._parent = {}  # node -> its parent node, None for a root; in the order they were added
        self._main_camera_node = None

    # The nodes and what they hold, as sets (pyrender's types).
    @property
    def nodes(self):
        return set(self._parent)

    def _holding(self, test):
        return {n for n in self._parent if test(n)}

    @property
    def mesh_nodes(self):
        return self._holding(lambda n: n.mesh is not None)

    @property
    def camera_nodes(self):
        return self._holding(lambda n: n.camera is not None)

    @property
    def light_nodes(self):
        return self._holding(lambda n: n.light is not None)

    @property
    def point_light_nodes(self):
        return self._holding(lambda n: isinstance(n.light, PointLight))

    @property
    def spot_light_nodes(self):
        return self._holding(lambda n: isinstance(n.light, SpotLight))

    @property
    def directional_light_nodes(self):
        return self._holding(lambda n: isinstance(n.light, DirectionalLight))

    @property
    def meshes(self):
        return {n.mesh for n in self.mesh_nodes}

    @property
    def cameras(self):
        return {n.camera for n in self.camera_nodes}

    @property
    def lights(self):
        return {n.light for n in self.light_nodes}

    @property
    def point_lights(self):
        return {n.light for n in self.point_light_nodes}

    @property
    def spot_lights(self):
        return {n.light for n in self.spot_light_nodes}

    @property
    def directional_lights(self):
        return {n.light for n in self.directional_light_nodes}

    @property
    def main_camera_node(self):
        """The camera node frames are drawn through: the first camera added, unless set."""
        return self._main_camera_node

    @main_camera_node.setter
    def main_camera_node(self, node):
        if node not in self._parent or node.camera is None:
            raise ValueError("main_camera_node: must be a camera node in this scene")
        self._main_camera_node = node

    # Bounds over every mesh, placed.
    @property
    def bounds(self):
        """2 x 3: the corners of the box around every placed mesh; zeros when there is none."""
        boxes = [posed_bounds(n.mesh.bounds, self.get_pose(n)[np.newaxis])
                 for n in self._parent if n.mesh is not None and n.mesh.primitives]
        if not boxes:
            return np.zeros((2, 3))
        boxes = np.array(boxes)
        return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])

    # Changing the tree.
    def add(self, obj, name=None, pose=None, parent_node=None, parent_name=None, node_id=None):
        """Places a Mesh, camera or light in a new node (under parent_node, or the one node named parent_name)
        and returns the node; the first camera becomes the main camera. node_id: its number in the id buffer."""
        if pose is not None:
            pose = np.asarray(pose, dtype=np.float64)
            if pose.shape != (4, 4) or not np.all(np.isfinite(pose)):
                raise ValueError(f"pose: expected a finite 4x4 matrix, got shape {pose.shape}")
        if isinstance(obj, Mesh):
            node = Node(name=name, matrix=pose, mesh=obj, id=node_id)
        elif isinstance(obj, Light):
            node = Node(name=name, matrix=pose, light=obj, id=node_id)
        elif isinstance(obj, Camera):
            node = Node(name=name, matrix=pose, camera=obj, id=node_id)
        else:
            raise TypeError(f"Scene.add: expected a Mesh, camera or light, got {type(obj).__name__}")
        if parent_node is None and parent_name is not None:
            named = self.get_nodes(name=parent_name)
            if len(named) != 1:
                raise ValueError(f"parent_name: {len(named)} nodes are named {parent_name!r}, not one")
            parent_node = next(iter(named))
        return self.add_node(node, parent_node=parent_node)

    def add_node(self, node, parent_node=None):
        """Adds node and its children's tree under parent_node (None: at the root)."""
        if not isinstance(node, Node):
            raise TypeError(f"Scene.add_node: expected a Node, got {type(node).__name__}")
        if node in self._parent:
            raise ValueError("Scene.add_node: the node is already in the scene")
        if parent_node is not None:
            if parent_node not in self._parent:
                raise ValueError("Scene.add_node: the parent node is not in the scene")
            if node not in parent_node.children:
                parent_node.children.append(node)
        if node.id is None:
            node.id = self._next_id
        if not isinstance(node.id, int) or not 0 <= node.id < 0xFFFFFFFF:
            raise ValueError(f"node_id: expected an integer in 0..2^32-2, got {node.id!r}")
        self._next_id = max(self._next_id, node.id + 1)
        self._parent[node] = parent_node
        if node.camera is not None and self._main_camera_node is None:
            self._main_camera_node = node
        for child in node.children:
            self.add_node(child, node)
        return node

    def has_node(self, node):
        return node in self._parent

    def remove_node(self, node):
        """Removes node and its tree of children; the node keeps its children, its parent loses it."""
        self._check(node)
        parent = self._parent[node]
        self._remove_tree(node)
        if parent is not None:
            parent.children.remove(node)

    def _remove_tree(self, node):
        del self._parent[node]
        for child in node.children:
            if child in self._parent:
                self._remove_tree(child)
        if node is self._main_camera_node:
            self._main_camera_node = next((n for n in self._parent if n.camera is not None), None)

    def get_nodes(self, node=None, name=None, obj=None, obj_name=None):
        """The set of this scene's nodes that are node, are named name, hold obj and hold an object named obj_name
        (each test made only when given)."""
        if node is not None:
            return {node} if node in self._parent else set()
        held = lambda n: (n.mesh, n.camera, n.light)  # noqa: E731
        return {n for n in self._parent if (name is None or n.name == name) and (obj is None or obj in held(n))
                and (obj_name is None or any(o is not None and o.name == obj_name for o in held(n)))}

    def get_pose(self, node):
        """node's pose in the world: its matrix, times its parents' up to the root."""
        self._check(node)
        pose = node.matrix
        parent = self._parent[node]
        while parent is not None:
            pose = parent.matrix @ pose
            parent = self._parent[parent]
        return pose

    @property
    def animations(self):
        """The animations of the file the scene was read from (Scene.from_file): (name, duration in seconds) each,
        in the file's order; empty for a file without, or a scene built otherwise."""
        return [] if self._motion is None else [tuple(a) for a in self._motion.animations()]

    def set_time(self, seconds, animation=None):
        """Poses what Scene.from_file placed `seconds` into one of the file's animations (its name or index; None:
        the first), clamped to the clip, as `facet render --time` does: the nodes' poses, and the meshes that skins
        and morph targets deform. Nodes removed from the scene since are skipped. Raises LoadError when the file
        has no such animation (or none), ValueError for a time that is not finite or a scene with no file's
        motion."""
        if self._motion is None:
            raise ValueError("set_time: the scene has no animation to play (Scene.from_file reads a file's)")
        posed = self._motion.pose(None if animation is None else str(animation), float(seconds))
        for (node, primitive), (pose, core) in zip(self._placed, posed):
            if node not in self._parent:
                continue
            node.matrix = pose
            if core is not None:
                primitive._core, primitive._box = core, core.bounds

    def set_pose(self, node, pose):
        """Sets node's matrix (relative to its parent) to pose."""
        self._check(node)
        node.matrix = pose

    def _check(self, node):
        if node not in self._parent:
            raise ValueError("the node is not in this scene")

    def _instances(self, only=None, flat=False):
        """(mesh core, world pose, node id, wireframe material) for each visible primitive and instance; only:
        the nodes to draw (None: all); flat: the meshes as RenderFlags.FLAT draws them."""
        out = []
        for node in self._parent:
            mesh = node.mesh
            if mesh is None or not mesh.is_visible or (only is not None and node not in only):
                continue
            pose = self.get_pose(node)
            for primitive in mesh.primitives:
                core = primitive._mesh_core(flat)
                if core is None:
                    continue
                material = primitive.material
                wireframe = bool(material is not None and material.wireframe)
                poses = [pose] if primitive.poses is None else pose @ primitive.poses
                out.extend((core, p, node.id, wireframe) for p in poses)
        return out

    def _placed_lights(self):
        """(light, world pose) of each light node, in the order they were added."""
        return [(node.light, self.get_pose(node)) for node in self._parent if node.light is not None]

    @staticmethod
    def from_trimesh_scene(trimesh_scene, bg_color=None, ambient_light=None):
        """A trimesh.Scene's geometry placed by its graph (read by duck typing), each as Mesh.from_trimesh makes
        it."""
        meshes = {name: Mesh.from_trimesh(geometry) for name, geometry in trimesh_scene.geometry.items()}
        scene = Scene(bg_color=bg_color, ambient_light=ambient_light)
        for node in trimesh_scene.graph.nodes_geometry:
            pose, geometry_name = trimesh_scene.graph[node]
            scene.add(meshes[geometry_name], pose=pose)
        return scene

    @staticmethod
    def from_file(path, bg_color=None, ambient_light=None, *, allow_external_files=False,
                  max_triangles=DEFAULT_MAX_TRIANGLES, max_points=DEFAULT_MAX_POINTS,
                  max_texture_size=DEFAULT_MAX_TEXTURE_SIZE):
        """Every mesh of a model file, placed by the file's nodes (node ids as the file numbers them), and the
        file's cameras. Reads within the limits Mesh.from_file takes, and raises as it does."""
        meshes, instances, cameras, motion = _facet.read_model(str(path), bool(allow_external_files), max_triangles,
                                                               max_points, max_texture_size)
        scene = Scene(bg_color=bg_color, ambient_light=ambient_light)
        wrapped = [Mesh([CorePrimitive(core)]) for core in meshes]
        placed = []
        for mesh_index, pose, node_id, deformed in instances:
            # A skinned or morphed instance gets a mesh of its own, which set_time replaces.
            mesh = Mesh([CorePrimitive(meshes[mesh_index])]) if deformed else wrapped[mesh_index]
            placed.append((scene.add(mesh, pose=pose, node_id=node_id), mesh.primitives[0] if deformed else None))
        scene._motion, scene._placed = motion, placed
        for c in cameras:
            if c["perspective"]:
                camera = PerspectiveCamera(c["yfov"], znear=c["znear"], zfar=c["zfar"], name=c["name"])
            else:
                camera = OrthographicCamera(c["xmag"], c["ymag"], znear=c["znear"], zfar=c["zfar"], name=c["name"])
            scene.add(camera, pose=c["pose"])
        return scene


__all__ = ["Scene"]
