"""Scenes made with pyrender's API alone, to be drawn by pyrender and by facet with the same calls."""
import numpy as np
import trimesh

from poses import look_at

SIZE = (320, 240)


def _stage(pr, ambient=(0.0, 0.0, 0.0)):
    scene = pr.Scene(bg_color=[0.0, 0.0, 0.0, 1.0], ambient_light=np.array(ambient))
    scene.add(pr.PerspectiveCamera(yfov=np.pi / 3.0, znear=0.1, zfar=20.0), pose=look_at((0.0, 0.0, 3.5)))
    return scene


def _sphere(pr, **material):
    look = pr.MetallicRoughnessMaterial(**material)
    return pr.Mesh.from_trimesh(trimesh.creation.icosphere(subdivisions=4, radius=1.0), material=look)


def _lit_sphere(ambient, material, light, position):
    """A scene of one sphere of `material` (MetallicRoughnessMaterial's keywords) lit by `light`, a function of pr
    making the light, placed at `position` looking at the sphere."""
    def make(pr):
        scene = _stage(pr, ambient)
        scene.add(_sphere(pr, **material))
        scene.add(light(pr), pose=look_at(position))
        return scene
    return make


directional = _lit_sphere((0.05, 0.05, 0.05), dict(baseColorFactor=[0.8, 0.3, 0.2, 1.0], metallicFactor=0.0,
                                                   roughnessFactor=0.5),
                          lambda pr: pr.DirectionalLight(color=np.ones(3), intensity=3.0), (1.0, 1.0, 2.0))
point = _lit_sphere((0.0, 0.0, 0.0), dict(baseColorFactor=[0.5, 0.5, 0.9, 1.0], metallicFactor=0.0,
                                          roughnessFactor=0.7),
                    lambda pr: pr.PointLight(color=np.ones(3), intensity=20.0), (1.5, 1.0, 2.0))
spot = _lit_sphere((0.0, 0.0, 0.0), dict(baseColorFactor=[0.9, 0.9, 0.9, 1.0], metallicFactor=0.0,
                                         roughnessFactor=0.6),
                   lambda pr: pr.SpotLight(color=np.ones(3), intensity=30.0, innerConeAngle=0.1,
                                           outerConeAngle=0.3), (0.0, 0.5, 3.0))
metal = _lit_sphere((0.1, 0.1, 0.1), dict(baseColorFactor=[0.9, 0.7, 0.3, 1.0], metallicFactor=1.0,
                                          roughnessFactor=0.35),
                    lambda pr: pr.DirectionalLight(color=np.ones(3), intensity=4.0), (-1.0, 1.0, 2.0))
rough_metal = _lit_sphere((0.02, 0.02, 0.02), dict(baseColorFactor=[0.95, 0.95, 0.95, 1.0], metallicFactor=1.0,
                                                   roughnessFactor=1.0),
                          lambda pr: pr.SpotLight(color=np.ones(3), intensity=25.0, innerConeAngle=0.2,
                                                  outerConeAngle=0.5), (0.5, 0.5, 3.0))


def face_colours(pr):
    """A box whose faces trimesh colours, drawn flat-sided with pyrender's white BLEND material for colours."""
    scene = _stage(pr, (0.1, 0.1, 0.1))
    box = trimesh.creation.box(extents=[1.5, 1.5, 1.5])
    palette = np.array([[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 0], [0, 255, 255], [255, 0, 255]])
    box.visual.face_colors = np.column_stack([np.repeat(palette, 2, axis=0), np.full(12, 255)]).astype(np.uint8)
    scene.add(pr.Mesh.from_trimesh(box, smooth=False), pose=look_at((0.0, 0.0, 0.0), (-1.0, -0.7, -1.2)))
    scene.add(pr.DirectionalLight(color=np.ones(3), intensity=3.0), pose=look_at((0.5, 1.0, 2.0)))
    return scene


def vertex_colours(pr):
    """A sphere coloured per vertex by its position, smooth, two lights."""
    scene = _stage(pr, (0.05, 0.05, 0.05))
    ball = trimesh.creation.icosphere(subdivisions=4, radius=1.0)
    ball.visual.vertex_colors = (np.clip(ball.vertices * 0.5 + 0.5, 0.0, 1.0) * 255).astype(np.uint8)
    scene.add(pr.Mesh.from_trimesh(ball))
    scene.add(pr.DirectionalLight(color=[1.0, 0.9, 0.8], intensity=2.5), pose=look_at((1.0, 1.0, 2.0)))
    scene.add(pr.PointLight(color=[0.6, 0.7, 1.0], intensity=8.0), pose=look_at((-2.0, -1.0, 2.0)))
    return scene


def textured(pr):
    """A quad with a checker texture and an emissive strip, lit from the front."""
    scene = _stage(pr, (0.1, 0.1, 0.1))
    checker = np.kron((np.indices((8, 8)).sum(axis=0) % 2), np.ones((16, 16)))
    image = np.stack([checker * 220 + 20, checker * 120 + 60, (1 - checker) * 200 + 30], axis=-1).astype(np.uint8)
    glow = np.zeros((128, 128, 3), dtype=np.uint8)
    glow[56:72] = (255, 128, 0)
    material = pr.MetallicRoughnessMaterial(baseColorTexture=image, emissiveTexture=glow,
                                            emissiveFactor=[1.0, 1.0, 1.0], metallicFactor=0.0, roughnessFactor=0.8)
    positions = np.array([[-1.2, -1.2, 0.0], [1.2, -1.2, 0.0], [1.2, 1.2, 0.0], [-1.2, 1.2, 0.0]])
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    quad = pr.Primitive(positions=positions, normals=np.tile([0.0, 0.0, 1.0], (4, 1)), texcoord_0=uv,
                        indices=np.array([[0, 1, 2], [0, 2, 3]]), material=material)
    scene.add(pr.Mesh([quad]), pose=look_at((0.0, 0.0, 0.0), (-0.4, -0.3, -1.0)))
    scene.add(pr.DirectionalLight(color=np.ones(3), intensity=2.0), pose=look_at((0.3, 0.5, 2.0)))
    return scene


def instanced(pr):
    """Nine instances of one box placed by poses, under a node turned and moved by its parent."""
    scene = _stage(pr, (0.1, 0.1, 0.1))
    poses = np.tile(np.eye(4), (9, 1, 1))
    poses[:, 0, 3] = np.repeat([-0.8, 0.0, 0.8], 3)
    poses[:, 1, 3] = np.tile([-0.8, 0.0, 0.8], 3)
    boxes = pr.Mesh.from_trimesh(trimesh.creation.box(extents=[0.4, 0.4, 0.4]), poses=poses,
                                 material=pr.MetallicRoughnessMaterial(baseColorFactor=[0.3, 0.7, 0.4, 1.0],
                                                                       metallicFactor=0.0, roughnessFactor=0.5))
    parent = pr.Node(rotation=[0.0, np.sin(0.3), 0.0, np.cos(0.3)], translation=[0.0, 0.2, 0.0])
    scene.add_node(parent)
    scene.add_node(pr.Node(mesh=boxes, matrix=look_at((0.0, 0.0, 0.0), (0.0, -0.3, -1.0))), parent_node=parent)
    scene.add(pr.DirectionalLight(color=np.ones(3), intensity=3.0), pose=look_at((1.0, 2.0, 2.0)))
    return scene


def points(pr):
    """A point cloud with a colour per point and no normals, under a directional light."""
    scene = _stage(pr, (0.1, 0.1, 0.1))
    rng = np.random.default_rng(7)
    cloud = rng.uniform(-1.0, 1.0, size=(4000, 3))
    cloud = cloud[np.linalg.norm(cloud, axis=1) < 1.0]
    colors = np.clip(cloud * 0.5 + 0.5, 0.0, 1.0)
    scene.add(pr.Mesh.from_points(cloud, colors=colors))
    scene.add(pr.DirectionalLight(color=np.ones(3), intensity=2.0), pose=look_at((1.0, 1.0, 2.0)))
    return scene


# name: (scene, flags as RenderFlags attribute names)
SCENES = {"directional": (directional, []), "point": (point, []), "spot": (spot, []), "metal": (metal, []), "rough_metal": (rough_metal, []),
          "face_colours": (face_colours, []), "vertex_colours": (vertex_colours, []), "textured": (textured, []),
          "instanced": (instanced, []), "points": (points, []), "flat": (directional, ["FLAT"])}


def render_all(pr):
    """{name: (color, depth)} of every scene, drawn by the pyrender-like module pr at SIZE."""
    renderer = pr.OffscreenRenderer(*SIZE)
    out = {}
    for name, (make, flag_names) in SCENES.items():
        flags = pr.RenderFlags.NONE
        for flag in flag_names:
            flags |= getattr(pr.RenderFlags, flag)
        out[name] = renderer.render(make(pr), flags)
    renderer.delete()
    return out
