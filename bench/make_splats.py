"""make_splats.py - a Gaussian splat scene standing in for a trained one: N Gaussians sampled on an OBJ mesh's
surface (area-weighted), coloured by position, small random-rotated anisotropic scales, opacity sigmoid(3), and
degree-3 spherical harmonics of small random coefficients, written in the 3D Gaussian Splatting paper's binary PLY
layout. Usage: make_splats.py MESH.obj N OUT.ply (needs numpy: Debian's python3-numpy)."""
import sys

import numpy as np

path, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
v, f = [], []
for line in open(path):
    p = line.split()
    if not p: continue
    if p[0] == 'v': v.append([float(x) for x in p[1:4]])
    elif p[0] == 'f':
        idx = [int(t.split('/')[0]) - 1 for t in p[1:]]
        for k in range(1, len(idx) - 1): f.append([idx[0], idx[k], idx[k + 1]])
v, f = np.array(v, np.float32), np.array(f)
a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
rng = np.random.default_rng(1)
t = rng.choice(len(f), n, p=area / area.sum())
r1, r2 = rng.random(n), rng.random(n)
s = np.sqrt(r1)
pos = (1 - s)[:, None] * a[t] + (s * (1 - r2))[:, None] * b[t] + (s * r2)[:, None] * c[t]
extent = np.linalg.norm(v.max(0) - v.min(0))
rest = 45
cols = ['x','y','z','nx','ny','nz','f_dc_0','f_dc_1','f_dc_2'] + [f'f_rest_{k}' for k in range(rest)] + ['opacity','scale_0','scale_1','scale_2','rot_0','rot_1','rot_2','rot_3']
data = np.zeros((n, len(cols)), np.float32)
data[:, 0:3] = pos
lo, hi = v.min(0), v.max(0)
data[:, 6:9] = ((pos - lo) / (hi - lo) - 0.5) / 0.2821
data[:, 9:9 + rest] = rng.normal(0, 0.05, (n, rest))
data[:, 9 + rest] = 3.0
data[:, 10 + rest:13 + rest] = np.log(extent * 0.002 * rng.uniform(0.5, 1.5, (n, 3)))
q = rng.normal(size=(n, 4)); data[:, 13 + rest:17 + rest] = q
with open(out, 'wb') as fo:
    fo.write(('ply\nformat binary_little_endian 1.0\nelement vertex %d\n' % n + ''.join('property float %s\n' % c for c in cols) + 'end_header\n').encode())
    fo.write(data.tobytes())
