#!/usr/bin/env bash
# fuzz.sh - fuzzes facet's readers of untrusted input with libFuzzer (Clang, ASan + UBSan).
# Usage: scripts/fuzz.sh --list            names the targets
#        scripts/fuzz.sh TARGET SECONDS    builds what is missing, then fuzzes TARGET for SECONDS from a seed corpus
#                                          of Debian's assimp-testmodels (environment: small files written here);
#                                          exits non-zero on any finding, whose input libFuzzer writes to
#                                          build-fuzz/findings/TARGET/.
# A finding, once fixed, joins tests/fuzz/regressions/FORMAT/, which every test run reads through the same reader.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
targets=(obj ply stl gltf xyz pcd splat image environment batch)
if [ "${1:-}" = --list ]; then
  printf '%s\n' "${targets[@]}"
  exit 0
fi
if [ $# -ne 2 ] || [[ ! " ${targets[*]} " =~ " $1 " ]] || [[ ! $2 =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh --list | scripts/fuzz.sh TARGET SECONDS (targets: ${targets[*]})" >&2
  exit 2
fi
target=$1 seconds=$2
scripts/deps.sh
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
[ -f build-fuzz/build.ninja ] || cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$(nproc)" --target "fuzz_$target" >/dev/null

# The seed corpus: real files of the target's formats, and the regression inputs.
models=/usr/share/assimp/models
corpus=build-fuzz/corpus/$target
findings=build-fuzz/findings/$target
mkdir -p "$corpus" "$findings"
seed() {  # seed FIND-ARGS...: copies matching files under 1000 KiB into the corpus, named by their content
  find "$models" -type f -size -1000k "$@" -print0 | while IFS= read -r -d '' f; do
    cp "$f" "$corpus/$(md5sum <"$f" | cut -c1-16)"
  done
}
case $target in
  obj) seed -iname '*.obj' ;;
  ply)
    seed -iname '*.ply'
    # No Gaussian splat scenes among the test models: the paper's layout in binary (degree 1) and ASCII (degree 0).
    python3 - "$corpus" <<'PY'
import struct, sys
out = sys.argv[1]
def splats(encoding, rest, rows):
    names = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"] + [f"f_rest_{k}" for k in range(rest)] + \
        ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    head = f"ply\nformat {encoding} 1.0\nelement vertex {len(rows)}\n" + \
        "".join(f"property float {n}\n" for n in names) + "end_header\n"
    row = lambda i: [i, 0.5, -1, 0.2, 0.4, 0.6] + [0.1] * rest + [1.5, -3, -2.5, -4, 1, 0.1, 0, 0]
    if encoding == "ascii":
        return head.encode() + "".join(" ".join(str(v) for v in row(i)) + "\n" for i in rows).encode()
    return head.encode() + b"".join(struct.pack(f"<{len(row(i))}f", *row(i)) for i in rows)
open(f"{out}/splats-binary", "wb").write(splats("binary_little_endian", 9, [0, 1, 2]))
open(f"{out}/splats-ascii", "wb").write(splats("ascii", 0, [0, 1]))
PY
    ;;
  stl) seed -iname '*.stl' ;;
  gltf) seed \( -iname '*.gltf' -o -iname '*.glb' \) ;;
  xyz)
    # No point clouds as text among the test models: one of each layout load_xyz reads, written here.
    printf '0 0 0\n1 2 3\n-1.5e3 4 5.25\n' >"$corpus/xyz3"
    printf '# x y z r g b\n0,0,0,255,0,0\n1,1,1,0,255,128\n' >"$corpus/xyz-rgb"
    printf '0 0 0 0 0 1\n1 0 0 0.6 0.8 0\n' >"$corpus/xyz-normals"
    printf '2\n0 0 0 -1200 255 255 255\n1 1 1 300 10 20 30\n' >"$corpus/pts"
    printf '0;0;0;0;0;1;10;20;30\r\n1;1;1;1;0;0;40;50;60\r\n' >"$corpus/xyz9"
    ;;
  pcd)
    # No PCD files among the test models: one per data encoding, written here (the compressed one's LZF stream is
    # literal runs, which any LZF decoder reads).
    python3 - "$corpus" <<'PY'
import struct, sys
out = sys.argv[1]
def header(fields, sizes, types, counts, n, data):
    return (f"# .PCD v0.7\nVERSION 0.7\nFIELDS {fields}\nSIZE {sizes}\nTYPE {types}\nCOUNT {counts}\n"
            f"WIDTH {n}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {data}\n").encode()
pts = [(0, 0, 0, 0x00ff0000), (1, 2, 3, 0x0000ff80), (float('nan'), 0, 0, 0)]
with open(f"{out}/ascii", "wb") as f:
    f.write(header("x y z rgb", "4 4 4 4", "F F F U", "1 1 1 1", 3, "ascii"))
    f.write(b"".join(f"{x} {y} {z} {c}\n".encode() for x, y, z, c in pts))
rows = b"".join(struct.pack("<fffI3f", x, y, z, c, 0, 0, 1) for x, y, z, c in pts)
with open(f"{out}/binary", "wb") as f:
    f.write(header("x y z rgba normal_x normal_y normal_z", "4 4 4 4 4 4 4", "F F F U F F F", "1 1 1 1 1 1 1", 3,
                   "binary") + rows)
by_field = struct.pack("<3f", *[p[0] for p in pts]) + struct.pack("<3f", *[p[1] for p in pts]) + \
    struct.pack("<3f", *[p[2] for p in pts])
lzf = b"".join(bytes([len(by_field[i:i + 32]) - 1]) + by_field[i:i + 32] for i in range(0, len(by_field), 32))
with open(f"{out}/compressed", "wb") as f:
    f.write(header("x y z", "4 4 4", "F F F", "1 1 1", 3, "binary_compressed") +
            struct.pack("<II", len(lzf), len(by_field)) + lzf)
PY
    ;;
  splat)
    # No .splat files among the test models: three Gaussians, one with a zero rotation, written here.
    python3 - "$corpus" <<'PY'
import struct, sys
rows = [((0, 0, 0), (0.1, 0.2, 0.3), (255, 128, 0, 200), (255, 128, 128, 128)),
        ((1, 0, -1), (0.5, 0.5, 0.5), (0, 0, 255, 255), (200, 160, 100, 128)),
        ((0, 1, 0), (0.2, 0.2, 0.2), (10, 20, 30, 40), (128, 128, 128, 128))]
open(f"{sys.argv[1]}/three", "wb").write(b"".join(struct.pack("<6f8B", *p, *s, *c, *r) for p, s, c, r in rows))
PY
    ;;
  image) seed \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.tga' -o -iname '*.bmp' \) ;;
  environment)
    # No environment images among the test models: small ones written here, each behind the byte that picks its
    # extension (fuzz_environment.cpp). OpenEXR: scanline half RGB, ZIP float Y, ZIPS with a layer and uint and
    # half channels, tiled float RGB; Radiance: flat and run-length.
    python3 - "$corpus" <<'PY'
import os, struct, sys, zlib
def attr(name, kind, value):
    return name.encode() + b'\0' + kind.encode() + b'\0' + struct.pack('<i', len(value)) + value
def header(channels, compression, w, h, tile=None):
    box = struct.pack('<4i', 0, 0, w - 1, h - 1)
    chlist = b''.join(n.encode() + b'\0' + struct.pack('<iB3xii', t, 0, 1, 1) for n, t in channels) + b'\0'
    attrs = [attr('channels', 'chlist', chlist), attr('compression', 'compression', bytes([compression])),
             attr('dataWindow', 'box2i', box), attr('displayWindow', 'box2i', box),
             attr('lineOrder', 'lineOrder', b'\0'), attr('pixelAspectRatio', 'float', struct.pack('<f', 1)),
             attr('screenWindowCenter', 'v2f', struct.pack('<2f', 0, 0)),
             attr('screenWindowWidth', 'float', struct.pack('<f', 1))]
    if tile: attrs.append(attr('tiles', 'tiledesc', struct.pack('<IIB', tile[0], tile[1], 0)))
    return b'v/1\x01' + struct.pack('<I', 2 | (0x200 if tile else 0)) + b''.join(attrs) + b'\0'
def pixels(channels, x0, y0, w, h):  # line by line, each channel's values in turn (types 0 uint, 1 half, 2 float)
    def value(t, x, y, c):
        v = 0.25 * ((3 * x + 5 * y + c) % 9)
        return struct.pack('<I', int(4 * v)) if t == 0 else struct.pack('<e' if t == 1 else '<f', v)
    return b''.join(value(t, x, y, c) for y in range(y0, y0 + h) for c, (_, t) in enumerate(channels)
                    for x in range(x0, x0 + w))
def zip_pack(raw):  # bytes split even then odd, differences, deflate; stored as they are unless smaller
    b = raw[0::2] + raw[1::2]
    d = bytes([b[0]] + [(b[i] - b[i - 1] + 384) & 0xff for i in range(1, len(b))])
    z = zlib.compress(d)
    return z if len(z) < len(raw) else raw
def exr(head, chunks):
    offsets, at = b'', len(head) + 8 * len(chunks)
    for chunk in chunks: offsets, at = offsets + struct.pack('<Q', at), at + len(chunk)
    return head + offsets + b''.join(chunks)
def scanline(channels, compression, w, h):  # compression 0 none, 2 ZIPS (a line a chunk), 3 ZIP (16 lines)
    lines, chunks = (16 if compression == 3 else 1), []
    for y in range(0, h, lines):
        raw = pixels(channels, 0, y, w, min(lines, h - y))
        data = zip_pack(raw) if compression else raw
        chunks.append(struct.pack('<2i', y, len(data)) + data)
    return exr(header(channels, compression, w, h), chunks)
def tiled(channels, w, h, tw, th):
    chunks = [struct.pack('<5i', tx, ty, 0, 0, len(data)) + data
              for ty in range((h + th - 1) // th) for tx in range((w + tw - 1) // tw)
              for data in [pixels(channels, tx * tw, ty * th, min(tw, w - tx * tw), min(th, h - ty * th))]]
    return exr(header(channels, 0, w, h, (tw, th)), chunks)
def radiance(w, h): return b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n' % (h, w)
rle_line = bytes([2, 2, 0, 10]) + bytes([136, 100, 2, 90, 80]) * 3 + bytes([136, 129, 2, 129, 129])
seeds = {
    'exr-half-rgb': scanline([('B', 1), ('G', 1), ('R', 1)], 0, 4, 3),
    'exr-zip-float-y': scanline([('Y', 2)], 3, 5, 20),
    'exr-zips-layer': scanline([('A', 1), ('diffuse.B', 2), ('diffuse.G', 0), ('diffuse.R', 1)], 2, 6, 3),
    'exr-tiled-rgb': tiled([('B', 2), ('G', 2), ('R', 2)], 5, 3, 2, 2),
    'hdr-flat': radiance(3, 2) + bytes([128, 64, 32, 129] * 6),
    'hdr-rle': radiance(10, 2) + rle_line * 2,
}
for name, data in seeds.items():
    open(os.path.join(sys.argv[1], name), 'wb').write(bytes([name.startswith('exr')]) + data)
PY
    ;;
  batch)
    printf '{"model": "a.obj", "output": "x/{stem}.png", "resolution": [64, 48], "no-background": true}\n' \
      >"$corpus/json"
    printf 'a.obj\n# comment\nb.glb\n' >"$corpus/list" ;;
esac
# Regression inputs; NAME.patch is a file of assimp-testmodels with some bytes changed (test_fuzz_regressions.cpp).
for input in tests/fuzz/regressions/"$target"/*; do
  [ -f "$input" ] || continue
  if [[ $input == *.patch ]]; then
    python3 - "$input" "$corpus/$(basename "$input" .patch)" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
data = bytearray(open(spec['base'], 'rb').read())
for offset, run in spec['patches']:
    data[offset:offset + len(run) // 2] = bytes.fromhex(run)
open(sys.argv[2], 'wb').write(data)
PY
  else
    cp "$input" "$corpus/"
  fi
done

echo "fuzz.sh: fuzzing $target for $seconds s from $(find "$corpus" -type f | wc -l) inputs" >&2
# -rss_limit_mb and -malloc_limit_mb: an input that makes a reader claim more than 2 GB is a finding too.
exec "build-fuzz/tests/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
  -malloc_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1
