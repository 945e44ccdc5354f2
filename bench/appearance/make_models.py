# make_models.py - writes the synthetic glTF 2.0 test models of the appearance comparison (self-contained .gltf files,
# buffers and images embedded as base64). Usage: python3 make_models.py OUT_DIR
import base64, json, os, struct, sys, zlib
import numpy as np

FLOAT, USHORT = 5126, 5123
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
NEAREST, REPEAT = 9728, 10497


def png_bytes(rgb):
    """An 8-bit RGB PNG of an (h, w, 3) uint8 array: filter 0 on every row, one IDAT."""
    h, w, _ = rgb.shape
    raw = b''.join(b'\0' + rgb[y].tobytes() for y in range(h))

    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


class Gltf:
    """Collects one binary buffer and the glTF arrays that index into it."""

    def __init__(self):
        self.data = bytearray()
        self.doc = {'asset': {'version': '2.0', 'generator': 'facet bench/appearance/make_models.py'},
                    'scene': 0, 'scenes': [{'nodes': []}], 'nodes': [], 'meshes': [], 'materials': [],
                    'accessors': [], 'bufferViews': [], 'buffers': []}

    def _add(self, key, item):
        self.doc.setdefault(key, []).append(item)
        return len(self.doc[key]) - 1

    def accessor(self, array, target):
        array = np.ascontiguousarray(array)
        view = self._add('bufferViews', {'buffer': 0, 'byteOffset': len(self.data), 'byteLength': array.nbytes,
                                         'target': target})
        self.data += array.tobytes()
        self.data += b'\0' * (-len(self.data) % 4)  # every view starts 4-byte aligned
        kind = {1: 'SCALAR', 2: 'VEC2', 3: 'VEC3', 4: 'VEC4'}[1 if array.ndim == 1 else array.shape[1]]
        acc = {'bufferView': view, 'componentType': FLOAT if array.dtype == np.float32 else USHORT,
               'count': len(array), 'type': kind}
        if array.dtype == np.float32:  # required on POSITION, harmless elsewhere
            acc['min'] = [float(v) for v in np.atleast_1d(array.min(axis=0))]
            acc['max'] = [float(v) for v in np.atleast_1d(array.max(axis=0))]
        return self._add('accessors', acc)

    def geometry(self, positions, normals, uvs, indices):
        """Accessors of one primitive, shared by every mesh made from it."""
        check_ccw(positions, normals, indices)
        return {'attributes': {'POSITION': self.accessor(positions.astype(np.float32), ARRAY_BUFFER),
                               'NORMAL': self.accessor(normals.astype(np.float32), ARRAY_BUFFER),
                               'TEXCOORD_0': self.accessor(uvs.astype(np.float32), ARRAY_BUFFER)},
                'indices': self.accessor(indices.astype(np.uint16).ravel(), ELEMENT_ARRAY_BUFFER)}

    def material(self, **fields):
        return self._add('materials', fields)

    def texture(self, rgb):
        image = self._add('images', {'uri': 'data:image/png;base64,' + base64.b64encode(png_bytes(rgb)).decode()})
        # Nearest filtering: the cells stay crisp, so the comparison does not hinge on either side's mip filtering.
        sampler = self._add('samplers', {'magFilter': NEAREST, 'minFilter': NEAREST, 'wrapS': REPEAT,
                                         'wrapT': REPEAT})
        return self._add('textures', {'source': image, 'sampler': sampler})

    def node(self, geometry, material=None, translation=(0, 0, 0), rotation=None):
        primitive = dict(geometry)
        if material is not None:
            primitive['material'] = material
        mesh = self._add('meshes', {'primitives': [primitive]})
        node = {'mesh': mesh, 'translation': [float(v) for v in translation]}
        if rotation is not None:
            node['rotation'] = rotation
        self.doc['scenes'][0]['nodes'].append(self._add('nodes', node))

    def write(self, path):
        doc = {k: v for k, v in self.doc.items() if v != []}
        doc['buffers'] = [{'byteLength': len(self.data),
                           'uri': 'data:application/octet-stream;base64,' + base64.b64encode(self.data).decode()}]
        with open(path, 'w') as f:
            json.dump(doc, f, indent=1)
            f.write('\n')


def check_ccw(positions, normals, indices):
    """Every triangle counter-clockwise seen from the side its normals point to."""
    a, b, c = (positions[indices[:, k]] for k in range(3))
    face = np.cross(b - a, c - a)
    assert (np.einsum('ij,ij->i', face, normals[indices].sum(axis=1)) > 0).all(), 'clockwise triangle'


def sphere(radius=1.0, segments=32, rings=16):
    theta = np.linspace(0, np.pi, rings + 1)[:, None]        # from the top (+Y) down
    phi = np.linspace(0, 2 * np.pi, segments + 1)[None, :]   # from +Z towards +X
    n = np.stack(np.broadcast_arrays(np.sin(theta) * np.sin(phi), np.cos(theta), np.sin(theta) * np.cos(phi)),
                 axis=-1).reshape(-1, 3)
    uv = np.stack(np.broadcast_arrays(phi / (2 * np.pi), theta / np.pi), axis=-1).reshape(-1, 2)
    tris = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            if i != rings - 1:
                tris.append((a, b, b + 1))  # skip the ones that collapse at the poles
            if i != 0:
                tris.append((a, b + 1, a + 1))
    return radius * n, n, uv, np.array(tris)


def cube(size=1.0):
    """24 vertices, so each face has its own normal and the whole texture."""
    faces = [((1, 0, 0), (0, 0, -1)), ((-1, 0, 0), (0, 0, 1)), ((0, 1, 0), (1, 0, 0)),
             ((0, -1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0)), ((0, 0, -1), (-1, 0, 0))]
    pos, nor, uv, tris = [], [], [], []
    for n, u in faces:
        n, u = np.array(n, float), np.array(u, float)
        v = np.cross(n, u)  # so that u x v = n
        base = len(pos)
        for su, sv, tex in ((-1, -1, (0, 1)), (1, -1, (1, 1)), (1, 1, (1, 0)), (-1, 1, (0, 0))):
            pos.append(size / 2 * (n + su * u + sv * v))
            nor.append(n)
            uv.append(tex)
        tris += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return np.array(pos), np.array(nor), np.array(uv), np.array(tris)


def quad(width, height):
    pos = np.array([(-width / 2, -height / 2, 0), (width / 2, -height / 2, 0), (width / 2, height / 2, 0),
                    (-width / 2, height / 2, 0)])
    return pos, np.tile([0.0, 0, 1], (4, 1)), np.array([(0, 1), (1, 1), (1, 0), (0, 0)]), np.array([(0, 1, 2),
                                                                                                     (0, 2, 3)])


def pbr(color, metallic, roughness, **extra):
    return dict(pbrMetallicRoughness={'baseColorFactor': list(color), 'metallicFactor': metallic,
                                      'roughnessFactor': roughness}, **extra)


# A turn of 30 degrees about y after a tilt of 20 degrees about x, so three faces of a cube show from the front.
def tilted():
    qx = np.array([np.sin(np.radians(10)), 0, 0, np.cos(np.radians(10))])
    qy = np.array([0, np.sin(np.radians(15)), 0, np.cos(np.radians(15))])
    (x1, y1, z1, w1), (x2, y2, z2, w2) = qy, qx
    q = [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
         w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]
    return [float(v) for v in q]


def sweep(out):
    """5x5 spheres: metallic 0..1 left to right, roughness 0..1 bottom to top."""
    g = Gltf()
    ball = g.geometry(*sphere(0.4))
    for i in range(5):
        for j in range(5):
            g.node(ball, g.material(**pbr((1.0, 0.5, 0.1, 1), i / 4, j / 4), name=f'm{i / 4:g}_r{j / 4:g}'),
                   translation=(i - 2, j - 2, 0))
    g.write(os.path.join(out, 'sweep.gltf'))


def default_material(out):
    """No material at all: the spec's default is white, metallic 1, roughness 1."""
    g = Gltf()
    g.node(g.geometry(*sphere()))
    g.write(os.path.join(out, 'default_material.gltf'))


def emissive(out):
    g = Gltf()
    box = g.geometry(*cube())
    glow = dict(emissiveFactor=[1, 0.4, 0.1])
    g.node(box, g.material(**pbr((0.05, 0.05, 0.05, 1), 0, 0.5, **glow)), (-0.8, 0, 0), tilted())
    g.node(box, g.material(**pbr((0.05, 0.05, 0.05, 1), 0, 0.5, **glow,
                                 extensions={'KHR_materials_emissive_strength': {'emissiveStrength': 2}})),
           (0.8, 0, 0), tilted())
    g.doc['extensionsUsed'] = ['KHR_materials_emissive_strength']
    g.write(os.path.join(out, 'emissive.gltf'))


def blend(out):
    """An opaque sphere, half covered by a half-transparent plane in front of it."""
    g = Gltf()
    g.node(g.geometry(*sphere(0.8)), g.material(**pbr((0.8, 0.8, 0.8, 1), 0, 0.4)), (0, 0, -0.5))
    g.node(g.geometry(*quad(1.4, 2.0)), g.material(**pbr((0.2, 0.6, 1.0, 0.5), 0, 0.5), alphaMode='BLEND'),
           (-0.5, 0, 0.6))
    g.write(os.path.join(out, 'blend.gltf'))


def factors(out):
    """0.604 is the linear value of sRGB 204 (0.8): a grey whose display value is easy to check."""
    g = Gltf()
    box = g.geometry(*cube())
    for x, color in ((-1.5, (0.604, 0.604, 0.604, 1)), (0, (0.5, 0.8, 0.9, 1)), (1.5, (1, 0, 0, 1))):
        g.node(box, g.material(**pbr(color, 0, 0.5)), (x, 0, 0), tilted())
    g.write(os.path.join(out, 'factors.gltf'))


def textured(out):
    """A 4x4 checker of base colours; metalness (blue) rising along u, roughness (green) along v."""
    g = Gltf()
    cells = (np.arange(16)[:, None] // 4 + np.arange(16)[None, :] // 4) % 2
    base = np.where(cells[..., None] == 1, np.array([230, 140, 40]), np.array([40, 110, 200])).astype(np.uint8)
    ramp = (np.arange(16) * 17).astype(np.uint8)
    mr = np.zeros((16, 16, 3), np.uint8)
    mr[..., 1] = ramp[:, None]   # roughness down the image
    mr[..., 2] = ramp[None, :]   # metalness across it
    material = g.material(pbrMetallicRoughness={'baseColorTexture': {'index': g.texture(base)},
                                                'metallicRoughnessTexture': {'index': g.texture(mr)}})
    g.node(g.geometry(*cube(1.2)), material, rotation=tilted())
    g.write(os.path.join(out, 'textured.gltf'))


def layers(out):
    """KHR_materials_clearcoat over a rough red (top row: coat 0, 0.5, 1 and a rough coat), KHR_materials_sheen over
    a dark blue (middle: white sheen rough to smooth, and a pink one), and both over a metal (bottom)."""
    g = Gltf()
    ball = g.geometry(*sphere(0.4))
    red, blue, gold = (0.8, 0.05, 0.02, 1), (0.02, 0.03, 0.2, 1), (1.0, 0.7, 0.3, 1)
    coat = lambda f, r: {'KHR_materials_clearcoat': {'clearcoatFactor': f, 'clearcoatRoughnessFactor': r}}
    sheen = lambda c, r: {'KHR_materials_sheen': {'sheenColorFactor': list(c), 'sheenRoughnessFactor': r}}
    rows = [[pbr(red, 0, 0.7, extensions=coat(f, r)) for f, r in ((0, 0), (0.5, 0), (1, 0), (1, 0.5))],
            [pbr(blue, 0, 0.8, extensions=sheen(c, r))
             for c, r in (((1, 1, 1), 1.0), ((1, 1, 1), 0.6), ((1, 1, 1), 0.3), ((1, 0.2, 0.6), 0.5))],
            [pbr(gold, 1, 0.5, extensions={**coat(1, 0.1), **sheen(s, 0.5)})
             for s in ((0, 0, 0), (0.3, 0.3, 0.3), (0.6, 0.6, 0.6), (1, 1, 1))]]
    for j, row in enumerate(rows):
        for i, material in enumerate(row):
            g.node(ball, g.material(**material, name=f'layers_{j}_{i}'), translation=(i - 1.5, 1 - j, 0))
    g.doc['extensionsUsed'] = ['KHR_materials_clearcoat', 'KHR_materials_sheen']
    g.write(os.path.join(out, 'layers.gltf'))


def glass(out):
    """KHR_materials_transmission: a clear and a green glass sphere, and a half-transmissive one, in front of a
    textured cube."""
    g = Gltf()
    base = np.zeros((64, 64, 3), np.uint8)
    base[(np.arange(64)[:, None] // 8 + np.arange(64)[None, :] // 8) % 2 == 0] = (230, 120, 30)
    base[(np.arange(64)[:, None] // 8 + np.arange(64)[None, :] // 8) % 2 == 1] = (30, 60, 200)
    g.node(g.geometry(*cube(2.4)), g.material(pbrMetallicRoughness={'baseColorTexture': {'index': g.texture(base)},
                                                                    'metallicFactor': 0, 'roughnessFactor': 0.8}),
           translation=(0, 0, -1.8))
    ball = g.geometry(*sphere(0.5))
    clear = lambda t: {'KHR_materials_transmission': {'transmissionFactor': t}}
    for x, color, t in ((-1.2, (1, 1, 1, 1), 1.0), (0, (0.2, 0.9, 0.3, 1), 1.0), (1.2, (0.9, 0.2, 0.2, 1), 0.5)):
        g.node(ball, g.material(**pbr(color, 0, 0.1, extensions=clear(t))), translation=(x, 0, 0))
    g.doc['extensionsUsed'] = ['KHR_materials_transmission']
    g.write(os.path.join(out, 'glass.gltf'))


def tangents(out):
    """A normal map of ridges on two cubes with TANGENT: on the left the tangents follow u, as the uvs' own frame
    would; on the right they are turned a quarter, so a renderer that ignored them would tilt the ridges the other
    way."""
    g = Gltf()
    u = np.linspace(0, 1, 64, endpoint=False)[None, :] + 1 / 128
    v = np.linspace(0, 1, 64, endpoint=False)[:, None] + 1 / 128
    n = np.stack(np.broadcast_arrays(0.6 * np.sin(8 * np.pi * u), 0.3 * np.sin(4 * np.pi * v), np.ones_like(u)),
                 axis=-1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    bumps = np.round((n * 0.5 + 0.5) * 255).astype(np.uint8)
    material = g.material(**pbr((0.8, 0.8, 0.8, 1), 0, 0.35, normalTexture={'index': g.texture(bumps)}))
    positions, normals, uvs, tris = cube(1.2)
    # Each face's u axis: the direction in which its uvs' u grows (cube() lays u along the face's second vector).
    along_u = np.array([positions[i + 1] - positions[i] for i in range(0, 24, 4) for _ in range(4)])
    along_u /= np.linalg.norm(along_u, axis=1, keepdims=True)
    for x, t in ((-0.9, along_u), (0.9, np.cross(normals, along_u))):
        geometry = g.geometry(positions, normals, uvs, tris)
        tangent = np.hstack([t, np.ones((24, 1))]).astype(np.float32)
        geometry['attributes'] = dict(geometry['attributes'], TANGENT=g.accessor(tangent, ARRAY_BUFFER))
        g.node(geometry, material, translation=(x, 0, 0), rotation=tilted())
    g.write(os.path.join(out, 'tangents.gltf'))


def main():
    if len(sys.argv) != 2:
        sys.exit('usage: make_models.py OUT_DIR')
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for make in (sweep, default_material, emissive, blend, factors, textured, layers, glass, tangents):
        make(out)
    print(f'{out}: sweep, default_material, emissive, blend, factors, textured, layers, glass, tangents (.gltf)')


if __name__ == '__main__':
    main()
