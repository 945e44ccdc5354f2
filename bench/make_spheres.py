#!/usr/bin/env python3
"""make_spheres.py - the benchmarks' two large generated meshes: UV spheres as a 200,704-triangle OBJ and an
870,400-triangle ASCII PLY. Usage: bench/make_spheres.py DIR (writes DIR/sphere200k.obj and DIR/sphere870k.ply)."""
import math
import sys


def sphere(rings, segments):
    v = [(math.sin(math.pi * r / rings) * math.cos(2 * math.pi * s / segments), math.cos(math.pi * r / rings),
          math.sin(math.pi * r / rings) * math.sin(2 * math.pi * s / segments))
         for r in range(rings + 1) for s in range(segments + 1)]
    f = []
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            f += [(a, b, a + 1), (a + 1, b, b + 1)]
    return v, f


def main(folder):
    v, f = sphere(224, 448)
    with open(folder + '/sphere200k.obj', 'w') as out:
        out.writelines(f'v {x:.6f} {y:.6f} {z:.6f}\n' for x, y, z in v)
        out.writelines(f'f {a + 1} {b + 1} {c + 1}\n' for a, b, c in f)
    v, f = sphere(512, 850)
    with open(folder + '/sphere870k.ply', 'w') as out:
        out.write(f'ply\nformat ascii 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\n'
                  f'property float z\nelement face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n')
        out.writelines(f'{x:.6f} {y:.6f} {z:.6f}\n' for x, y, z in v)
        out.writelines(f'3 {a} {b} {c}\n' for a, b, c in f)


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
