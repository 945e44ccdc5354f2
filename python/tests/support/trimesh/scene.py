"""Scene: named geometry placed by a graph of named nodes, each with a transform relative to its parent."""
import collections

import numpy as np


class SceneGraph:
    """Nodes under a base frame. Each node has a parent, a 4 x 4 transform relative to it and optionally the name
    of the geometry it places; graph[node] gives (world transform, geometry name)."""

    def __init__(self, base_frame="world"):
        self.base_frame = base_frame
        # node name -> (parent name, local 4 x 4, geometry name or None), in insertion order.
        self._nodes = collections.OrderedDict()

    def update(self, frame_to, frame_from=None, matrix=None, geometry=None, **kwargs):
        """Add or change node `frame_to` under `frame_from` (the base frame by default), keeping what is not given."""
        if frame_to == self.base_frame:
            raise ValueError(f"the base frame {self.base_frame!r} cannot be a child")
        parent, local, geom = self._nodes.get(frame_to, (self.base_frame, np.eye(4), None))
        if frame_from is not None:
            if frame_from != self.base_frame and frame_from not in self._nodes:
                raise ValueError(f"parent node {frame_from!r} is not in the graph")
            parent = frame_from
        if matrix is not None:
            local = np.array(matrix, dtype=np.float64)
            if local.shape != (4, 4):
                raise ValueError(f"node {frame_to!r}: transform must be 4 x 4, got shape {local.shape}")
        self._nodes[frame_to] = (parent, local, geometry if geometry is not None else geom)

    @property
    def nodes(self):
        return [self.base_frame] + list(self._nodes)

    @property
    def nodes_geometry(self):
        """The names of the nodes that place geometry, in the order they were added."""
        return [name for name, (_, _, geom) in self._nodes.items() if geom is not None]

    def parent(self, node):
        return self._nodes[node][0]

    def get(self, frame_to, frame_from=None):
        """(4 x 4 transform of `frame_to` in `frame_from`'s frame (the base frame by default), geometry name)."""
        world, geometry = self._world(frame_to)
        if frame_from is not None and frame_from != self.base_frame:
            world = np.linalg.inv(self._world(frame_from)[0]) @ world
        return world, geometry

    def __getitem__(self, node):
        return self.get(node)

    def __contains__(self, node):
        return node == self.base_frame or node in self._nodes

    def _world(self, node):
        if node == self.base_frame:
            return np.eye(4), None
        if node not in self._nodes:
            raise KeyError(node)
        _, _, geometry = self._nodes[node]
        world, seen = np.eye(4), set()
        while node != self.base_frame:
            if node in seen:
                raise ValueError(f"node {node!r} is its own ancestor")
            seen.add(node)
            parent, local, _ = self._nodes[node]
            world = local @ world
            node = parent
        return world, geometry

    def copy(self):
        other = SceneGraph(self.base_frame)
        for name, (parent, local, geom) in self._nodes.items():
            other._nodes[name] = (parent, local.copy(), geom)
        return other


def _unique_name(name, taken):
    """`name`, or `name_1`, `name_2`, ... for the first that is not taken."""
    if name not in taken:
        return name
    index = 1
    while f"{name}_{index}" in taken:
        index += 1
    return f"{name}_{index}"


class Scene:
    """Geometry by name (an ordered dict of Trimesh) and a SceneGraph placing it."""

    def __init__(self, geometry=None, base_frame="world", graph=None, metadata=None, **kwargs):
        self.geometry = collections.OrderedDict()
        self.graph = SceneGraph(base_frame) if graph is None else graph
        self.metadata = dict(metadata or {})
        if isinstance(geometry, dict):
            for name, mesh in geometry.items():
                self.add_geometry(mesh, geom_name=name)
        elif geometry is not None:
            for mesh in geometry if isinstance(geometry, (list, tuple)) else [geometry]:
                self.add_geometry(mesh)

    def add_geometry(self, geometry, node_name=None, geom_name=None, parent_node_name=None, transform=None,
                     **kwargs):
        """Add a mesh under a unique geometry name and place it with a new node; returns the node's name."""
        name = geom_name or getattr(geometry, "metadata", {}).get("name") or "geometry_0"
        geom_name = _unique_name(name, self.geometry)
        self.geometry[geom_name] = geometry
        node_name = _unique_name(node_name or geom_name, set(self.graph.nodes))
        self.graph.update(node_name, frame_from=parent_node_name,
                          matrix=np.eye(4) if transform is None else transform, geometry=geom_name)
        return node_name

    @property
    def is_empty(self):
        return len(self.geometry) == 0

    def dump(self, concatenate=False):
        """A copy of the geometry at every node that places some, moved into world space; one mesh if
        `concatenate`."""
        meshes = []
        for node in self.graph.nodes_geometry:
            transform, geom_name = self.graph[node]
            meshes.append(self.geometry[geom_name].copy().apply_transform(transform))
        if concatenate:
            from .util import concatenate as join
            return join(meshes)
        return meshes

    @property
    def bounds(self):
        """2 x 3 [min, max] corners of all placed geometry in world space, or None for an empty scene."""
        boxes = [mesh.bounds for mesh in self.dump() if mesh.bounds is not None]
        if not boxes:
            return None
        boxes = np.array(boxes)
        return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])

    @property
    def extents(self):
        bounds = self.bounds
        return None if bounds is None else bounds[1] - bounds[0]

    @property
    def centroid(self):
        bounds = self.bounds
        return None if bounds is None else bounds.mean(axis=0)

    @property
    def scale(self):
        extents = self.extents
        return 0.0 if extents is None else float(np.linalg.norm(extents))

    def copy(self):
        other = Scene(base_frame=self.graph.base_frame, graph=self.graph.copy(), metadata=self.metadata)
        for name, mesh in self.geometry.items():
            other.geometry[name] = mesh.copy()
        return other

    def __repr__(self):
        return f"<trimesh.Scene(len(geometry)={len(self.geometry)})>"
