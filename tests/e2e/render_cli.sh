#!/usr/bin/env bash
# render_cli.sh - `facet render` and `facet info` on real OBJ, PLY and STL files: sizes, framing, projections, shadings,
# depth output.
# Usage: render_cli.sh FACET SCRATCH. Prints one line per check and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
models=/usr/share/assimp/models/OBJ
ply_models=/usr/share/assimp/models/PLY
stl_models=/usr/share/assimp/models/STL
mkdir -p "$scratch"
rm -f "$scratch"/*.png "$scratch"/*.npy "$scratch"/*.exr

# PNG / .npy checks: the shared PNG reader (lib/png.py) followed by this script's commands.
check=$scratch/check.py
cat "$e2e_lib/png.py" - >"$check" <<'EOF'
import ast, array  # struct and sys come with png.py

def model_mask(w, h, ch, rows):
    """One bytes object per row, 1 where the pixel is model; whole rows at a time, as pure python is slow per pixel."""
    # Background = the top-left pixel's colour (auto-framed models never reach the corner).
    bg = rows[0][:ch]
    far = [bytes(int(abs(v - bg[k]) > 2) for v in range(256)) for k in range(ch)]
    mask = []
    for row in rows:
        bits = 0
        for k in range(ch):
            bits |= int.from_bytes(row[k::ch].translate(far[k]), 'big')
        mask.append(bits.to_bytes(w, 'big'))
    return mask

def bbox(mask):
    ys = [y for y, r in enumerate(mask) if r.count(1)]
    columns = 0
    for r in mask:
        columns |= int.from_bytes(r, 'big')
    cols = columns.to_bytes(len(mask[0]), 'big')
    xs = (len(cols) - len(cols.lstrip(b'\0')), len(cols.rstrip(b'\0')) - 1)
    return (xs[0], min(ys), xs[1], max(ys)) if ys else None

cmd, path = sys.argv[1], sys.argv[2]
if cmd == 'image':  # image FILE W H [inside]: size, 1%..99% model pixels, optionally clear of the border
    w, h, ch, rows = read_png(path)
    if (w, h) != (int(sys.argv[3]), int(sys.argv[4])):
        sys.exit(f'size {w}x{h}, expected {sys.argv[3]}x{sys.argv[4]}')
    mask = model_mask(w, h, ch, rows)
    frac = sum(r.count(1) for r in mask) / (w * h)
    box = bbox(mask)
    if not 0.01 <= frac <= 0.99:
        sys.exit(f'model covers {frac:.1%} of the image')
    if len(sys.argv) > 5 and (box[0] == 0 or box[1] == 0 or box[2] == w - 1 or box[3] == h - 1):
        sys.exit(f'model touches the border: bbox {box}')
    print(f'{w}x{h}, model {frac:.1%}, bbox {box}')
elif cmd == 'bbox-height':  # bbox-height FILE LO HI
    w, h, ch, rows = read_png(path)
    box = bbox(model_mask(w, h, ch, rows))
    height = box[3] - box[1] + 1
    if not float(sys.argv[3]) <= height <= float(sys.argv[4]):
        sys.exit(f'model is {height} px tall (bbox {box}), expected {sys.argv[3]}..{sys.argv[4]}')
    print(f'model {height} px tall')
elif cmd == 'apex-up':  # apex-up FILE: the first row of the model is narrower than its last (a pyramid, apex up)
    w, h, ch, rows = read_png(path)
    mask = model_mask(w, h, ch, rows)
    box = bbox(mask)
    top, bottom = sum(mask[box[1] + 2]), sum(mask[box[3] - 2])
    if not top < bottom:
        sys.exit(f'apex not at the top: {top} model pixels near the top row, {bottom} near the bottom')
    print(f'apex up ({top} px near the top, {bottom} near the bottom)')
elif cmd == 'depth':  # depth FILE.npy PNG(RGBA): shape (H, W) float32, 0 where the PNG is transparent, > 0 where opaque
    # Anti-aliased, a pixel at a silhouette is partly covered (0 < alpha < 255) and its depth is sample 0's, which
    # may or may not be covered.
    data = open(path, 'rb').read()
    if data[:6] != b'\x93NUMPY':
        sys.exit('not a .npy file')
    n = struct.unpack('<H', data[8:10])[0]
    header = ast.literal_eval(data[10:10 + n].decode('latin1'))
    w, h, ch, rows = read_png(sys.argv[3])
    if header['descr'] != '<f4' or header['fortran_order'] or header['shape'] != (h, w):
        sys.exit(f'header {header}, expected <f4 C-order ({h}, {w})')
    values = array.array('f')
    values.frombytes(data[10 + n:])
    if len(values) != w * h:
        sys.exit(f'{len(values)} values for {w}x{h}')
    bad = inside = 0
    for y in range(h):
        for x in range(w):
            d, alpha = values[y * w + x], rows[y][x * 4 + 3]
            inside += alpha > 0
            if (alpha == 0 and d > 0) or (alpha == 255 and not d > 0) or not d < float('inf') or d < 0:
                bad += 1
    if inside == 0 or bad > 0.002 * w * h:
        sys.exit(f'{bad} pixels where depth and coverage disagree ({inside} covered)')
    print(f'({h}, {w}) float32, {inside} pixels with depth')
elif cmd == 'rgba':  # rgba FILE: an RGBA PNG whose corner is transparent
    w, h, ch, rows = read_png(path)
    if ch != 4 or rows[0][3] != 0:
        sys.exit(f'{ch} channels, corner alpha {rows[0][ch - 1]}')
    print('RGBA, transparent background')
EOF

# run NAME CHECK-ARGS... -- FACET-ARGS...: renders NAME.png with the facet args, then runs check.py on it.
run() {
  local name=$1; shift
  local checks=()
  while [ "$1" != "--" ]; do checks+=("$1"); shift; done
  shift
  local out=$scratch/$name.png
  if ! "$facet" "$@" --output "$out" 2>"$scratch/$name.log"; then
    bad "$name" "facet $* failed: $(head -n 2 "$scratch/$name.log")"
    return
  fi
  local result
  if result=$(python3 "$check" "${checks[0]}" "$out" "${checks[@]:1}" 2>&1); then
    ok "$name: $result"
  else
    bad "$name" "$result"
  fi
}

# Real models, auto-framed: the requested size, the model in view and clear of the border.
for model in WusonOBJ spider box cube_with_vertexcolors; do
  run "model_$model" image 320 240 inside -- render "$models/$model.obj" --resolution 320,240
done
run default_size image 1024 768 inside -- render "$models/box.obj"

# The native PLY and STL readers, on real files: an ASCII PLY with normals and uvs, a binary STL.
run model_ply image 320 240 inside -- render "$ply_models/Wuson.ply" --resolution 320,240
run model_stl image 320 240 inside -- render "$stl_models/Spider_binary.stl" --resolution 320,240

# Point clouds, drawn as points: a real PLY of coloured points with normals, and text clouds, squares and discs.
run cloud_ply image 320 240 -- render "$ply_models/points.ply" --resolution 320,240 --point-size 40
python3 -c 'import math
for i in range(2000):
    t = i * 0.01
    print(f"{math.cos(t * 7):.4f} {math.sin(t * 7):.4f} {t / 20 - 0.5:.4f} {i % 256} 128 {255 - i % 256}")' \
  >"$scratch/helix.xyz"
run cloud_xyz image 320 240 inside -- render "$scratch/helix.xyz" --resolution 320,240
run cloud_discs image 320 240 inside -- render "$scratch/helix.xyz" --resolution 320,240 --point-shape disc \
  --point-size 5
# PCL's PCD, ASCII with a packed colour per point (PCL writes rgb's bits as a float: 0x00ff8000 here).
python3 -c 'import math, struct
rgb = struct.unpack("<f", struct.pack("<I", 0x00ff8000))[0]
print("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 2000")
print("HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2000\nDATA ascii")
for i in range(2000):
    t = i * 0.01
    print(f"{math.cos(t * 7):.4f} {math.sin(t * 7):.4f} {t / 20 - 0.5:.4f} {rgb!r}")' >"$scratch/helix.pcd"
run cloud_pcd image 320 240 inside -- render "$scratch/helix.pcd" --resolution 320,240 --point-size 3
# A Gaussian splat scene in the 3D Gaussian Splatting paper's PLY layout: 2,000 Gaussians on a sphere, coloured by
# where they are (degree 0: f_dc = (colour - 0.5) / 0.2821), in a turntable too.
python3 -c 'import math, random, struct, sys
random.seed(1)
props = ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
         "rot_0", "rot_1", "rot_2", "rot_3"]
out = sys.stdout.buffer
out.write(("ply\nformat binary_little_endian 1.0\nelement vertex 2000\n" +
           "".join(f"property float {p}\n" for p in props) + "end_header\n").encode())
for i in range(2000):
    u, v = random.random() * 2 * math.pi, math.acos(2 * random.random() - 1)
    p = (math.sin(v) * math.cos(u), math.sin(v) * math.sin(u), math.cos(v))
    out.write(struct.pack("<14f", *p, *[(0.5 + 0.5 * c - 0.5) / 0.28209479 for c in p], 2.0,
                          *[math.log(0.05)] * 3, 1, 0, 0, 0))' >"$scratch/splats.ply"
run splats_ply image 320 240 inside -- render "$scratch/splats.ply" --resolution 320,240
if "$facet" render "$scratch/splats.ply" --turntable 4 --resolution 96,72 --output "$scratch/splats.gif" \
  2>"$scratch/splats.err" && msg=$(python3 "$e2e_lib/gif.py" "$scratch/splats.gif" 96 72 4 75 2>&1); then
  ok "splat turntable GIF: $msg"
else
  bad "splat turntable GIF" "${msg:-$(cat "$scratch/splats.err")}"
fi
# A scan's intensity as a grey ramp: points along x whose intensity rises with x, on a red background.
python3 -c '
for k in range(200):
    print(k / 100 - 1, (k % 10) / 50, 0, 20 + 3 * k)' >"$scratch/ramp.xyz"
if "$facet" render "$scratch/ramp.xyz" --color-map intensity --point-size 4 --background-color 1,0,0 --samples 1 \
  --resolution 240,120 --output "$scratch/ramp.png" 2>"$scratch/ramp.log" &&
  msg=$(cat "$e2e_lib/png.py" - <<'PY' | python3 - "$scratch/ramp.png" 2>&1
import sys
w, h, ch, rows = read_png(sys.argv[1])
pixels = [tuple(row[i:i + 3]) for row in rows for i in range(0, w * ch, ch)]
drawn = [p for p in pixels if p != (255, 0, 0)]
greys = [p[0] for p in drawn if p[0] == p[1] == p[2]]
assert len(greys) > 0.9 * len(drawn) > 200, f"{len(greys)} grey of {len(drawn)} drawn pixels"
assert min(greys) < 40 and max(greys) > 215, f"greys from {min(greys)} to {max(greys)}"
drawn_at = sorted((i % w, p[0]) for i, p in enumerate(pixels) if p != (255, 0, 0))
half = len(drawn_at) // 2
left, right = [g for _, g in drawn_at[:half]], [g for _, g in drawn_at[half:]]
assert sum(left) / len(left) + 60 < sum(right) / len(right), "darker on the left, where the intensity is low"
print(f"{len(drawn)} points' pixels, grey {min(greys)} to {max(greys)}, darker to the left")
PY
); then
  ok "--color-map intensity: $msg"
else
  bad "--color-map intensity" "${msg:-$(cat "$scratch/ramp.log")}"
fi
for bad_points in "--point-size 0" "--point-size 300" "--point-shape star" "--eye-dome-lighting -1" \
  "--eye-dome-lighting 101" "--color-map rainbow" "--color-map height --color 1,0,0" "--color-map intensity"; do
  # shellcheck disable=SC2086  # the flags are meant to split
  if "$facet" render "$scratch/helix.xyz" $bad_points --output "$scratch/bad_points.png" 2>"$scratch/bad_points.log"; then
    bad "$bad_points" "accepted"
  elif [ "$(wc -l <"$scratch/bad_points.log")" = 1 ] && [ ! -e "$scratch/bad_points.png" ]; then
    ok "$bad_points: $(cat "$scratch/bad_points.log")"
  else
    bad "$bad_points" "$(head -n 2 "$scratch/bad_points.log")"
  fi
done

# Every projection and shading renders with the model in view.
for p in perspective orthographic frustum oblique isometric dimetric trimetric front top side; do
  run "projection_$p" image 160 120 inside -- render "$models/WusonOBJ.obj" --projection "$p" --resolution 160,120
done
run frustum_window image 160 120 -- render "$models/box.obj" --projection frustum --frustum -0.1,0.05,-0.05,0.05 \
  --near 0.2 --far 10 --camera-position 0,0,3 --resolution 160,120
run oblique_cavalier image 160 120 inside -- render "$models/box.obj" --projection oblique --oblique-angle 30 \
  --oblique-scale 1 --resolution 160,120
for s in unlit flat gouraud phong blinn-phong normals depth; do
  run "shading_$s" image 160 120 inside -- render "$models/spider.obj" --shading "$s" --resolution 160,120
done

# Drawing modes and look flags.
run wireframe image 160 120 inside -- render "$models/WusonOBJ.obj" --wireframe --resolution 160,120
run edges image 160 120 inside -- render "$models/box.obj" --edges --resolution 160,120
for c in back front none; do
  run "culling_$c" image 160 120 inside -- render "$models/spider.obj" --culling "$c" --resolution 160,120
done
run no_depth_test image 160 120 inside -- render "$models/box.obj" --no-depth-test --resolution 160,120
run painter image 160 120 inside -- render "$models/spider.obj" --painter --resolution 160,120
run look image 160 120 inside -- render "$models/box.obj" --background-color 1,1,1 --color 0.8,0.2,0.1 \
  --light-direction 1,1,1 --threads 2 --resolution 160,120
run camera_angles image 160 120 inside -- render "$models/WusonOBJ.obj" --camera-azimuth-angle 90 \
  --camera-elevation-angle -30 --camera-view-angle 40 --resolution 160,120
run no_background rgba -- render "$models/box.obj" --no-background --resolution 160,120

# An explicit camera neither moves nor scales the model: the unit box seen from (0,0,5) with a 30 degree view angle
# spans 0.5 / 4.5 / tan(15 deg) = 0.4147 of the image height, 99.5 of 240 pixels (its front face is 4.5 away).
run camera_position bbox-height 97 102 -- render "$models/box.obj" --camera-position 0,0,5 \
  --camera-focal-point 0,0,0 --camera-view-angle 30 --resolution 240,240

# Right way up, and --up +Z: a pyramid with its apex up the model's up axis shows the apex at the top.
printf 'v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 2 0\nf 1 2 3 4\nf 4 3 5\nf 3 2 5\nf 2 1 5\nf 1 4 5\n' \
  >"$scratch/pyramid_y.obj"
printf 'v -1 1 0\nv 1 1 0\nv 1 -1 0\nv -1 -1 0\nv 0 0 2\nf 1 2 3 4\nf 4 3 5\nf 3 2 5\nf 2 1 5\nf 1 4 5\n' \
  >"$scratch/pyramid_z.obj"
run up_y apex-up -- render "$scratch/pyramid_y.obj" --projection front --culling none --resolution 160,120
run up_z apex-up -- render "$scratch/pyramid_z.obj" --up +Z --projection front --culling none --resolution 160,120
run up_z_perspective apex-up -- render "$scratch/pyramid_z.obj" --up +Z --culling none --resolution 160,120

# --output-depth: float32 H x W, 0 exactly where nothing was drawn.
for p in perspective orthographic; do
  name=depth_$p
  if "$facet" render "$models/spider.obj" --projection "$p" --resolution 96,64 --no-background \
    --output "$scratch/$name.png" --output-depth "$scratch/$name.npy" 2>"$scratch/$name.log" &&
    result=$(python3 "$check" depth "$scratch/$name.npy" "$scratch/$name.png" 2>&1); then
    ok "$name: $result"
  else
    bad "$name" "${result:-$(head -n 2 "$scratch/$name.log")}"
  fi
done

# --output-mask and --output-camera: written beside the image, the camera as JSON with OpenCV intrinsics.
if "$facet" render "$models/box.obj" --resolution 64,48 --output "$scratch/mc.png" \
  --output-mask "$scratch/mc_mask.png" --output-camera "$scratch/mc.json" 2>"$scratch/mc.log" &&
  python3 -c 'import json, sys
c = json.load(open(sys.argv[1]))
assert (c["width"], c["height"], c["projection"]) == (64, 48, "perspective"), c
assert len(c["K"]) == 3 and c["K"][2] == [0, 0, 1] and c["K"][0][0] > 0, c["K"]
assert len(c["camera_from_world"]) == 4 and c["near"] < c["far"], c' "$scratch/mc.json" &&
  [ "$(head -c 8 "$scratch/mc_mask.png" | od -An -tx1 | tr -d ' ')" = 89504e470d0a1a0a ]; then
  ok "mask and camera"
else
  bad "mask and camera" "$(head -n 2 "$scratch/mc.log")"
fi

# --output-normal and --output-ids: .exr by extension, ids as uint32 (H, W, 2) .npy.
if "$facet" render "$models/box.obj" --resolution 64,48 --output "$scratch/ni.png" --output-depth "$scratch/ni_d.exr" \
  --output-normal "$scratch/ni_n.exr" --output-ids "$scratch/ni_i.npy" 2>"$scratch/ni.log" &&
  [ "$(head -c 4 "$scratch/ni_n.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] &&
  [ "$(head -c 4 "$scratch/ni_d.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] &&
  head -c 128 "$scratch/ni_i.npy" | grep -aq "'descr': '<u4', 'fortran_order': False, 'shape': (48, 64, 2)"; then
  ok "normal and ids"
else
  bad "normal and ids" "$(head -n 2 "$scratch/ni.log")"
fi

# Several models, one command: output names from {stem} and {n:02}; a broken model is reported, the rest render.
mkdir -p "$scratch/many"
rm -f "$scratch/many"/*
printf 'not a model\n' >"$scratch/many/broken.obj"
"$facet" render "$models/box.obj" "$scratch/many/broken.obj" "$stl_models/Spider_binary.stl" --resolution 64,48 \
  --output "$scratch/many/{n:02}_{stem}.png" --output-mask "$scratch/many/{stem}_mask.png" 2>"$scratch/many.log"
status=$?
made=$(cd "$scratch/many" && ls ./*.png 2>/dev/null | tr '\n' ' ')
if [ "$status" = 1 ] && [ "$(grep -c '^facet: error: .*broken.obj' "$scratch/many.log")" = 1 ] &&
  [ "$made" = "./00_box.png ./02_Spider_binary.png ./Spider_binary_mask.png ./box_mask.png " ]; then
  ok "several models: $made"
else
  bad "several models" "exit $status, made: $made; $(head -n 2 "$scratch/many.log")"
fi

# --timings: one line per render on stderr with every stage, the peak memory, the page faults and the CPU level.
stages='load [0-9.]+ ms, prepare [0-9.]+ ms, draw [0-9.]+ ms, write [0-9.]+ ms, total [0-9.]+ ms'
if "$facet" render "$models/box.obj" --resolution 64,48 --output "$scratch/timed.png" --timings 2>"$scratch/timed.log" &&
  [ "$(wc -l <"$scratch/timed.log")" = 1 ] &&
  grep -Eq "^facet: timings: .*box.obj: $stages, peak memory [0-9.]+ MiB, page faults [1-9][0-9]*, (avx512|avx2|sse4|baseline)\$" "$scratch/timed.log"; then
  ok "--timings: $(cat "$scratch/timed.log")"
else
  bad "--timings" "$(head -n 2 "$scratch/timed.log")"
fi
# Under FACET_CPU=baseline it names the level that ran: the baseline, on every x86-64 CPU.
if [ "$(uname -m)" = x86_64 ] &&
  ! { FACET_CPU=baseline "$facet" render "$models/box.obj" --resolution 64,48 --output "$scratch/timed.png" \
    --timings 2>&1 | grep -Eq ", baseline\$"; }; then
  bad "--timings under FACET_CPU=baseline" "does not name the baseline"
else
  ok "--timings under FACET_CPU=baseline names it"
fi
# An unknown FACET_CPU stops the render with one line, and writes no image.
rm -f "$scratch/cpu.png"
if FACET_CPU=fastest "$facet" render "$models/box.obj" --output "$scratch/cpu.png" 2>"$scratch/cpu.log"; then
  bad "FACET_CPU=fastest" "accepted"
elif [ "$(wc -l <"$scratch/cpu.log")" = 1 ] && grep -q "FACET_CPU=fastest: not a CPU level" "$scratch/cpu.log" &&
  [ ! -e "$scratch/cpu.png" ]; then
  ok "FACET_CPU=fastest: $(cat "$scratch/cpu.log")"
else
  bad "FACET_CPU=fastest" "$(head -n 3 "$scratch/cpu.log")"
fi

# facet info: counts and bounds, one item per line.
if info=$("$facet" info "$models/box.obj" 2>"$scratch/info.log") &&
  grep -qx 'vertices: 8' <<<"$info" && grep -qx 'triangles: 12' <<<"$info" && grep -qx 'edges: 18' <<<"$info" &&
  grep -qx 'materials: 0' <<<"$info" && grep -qx 'lights: 0' <<<"$info" &&
  grep -qx 'bounds min: -0.5 -0.5 -0.5' <<<"$info" &&
  grep -qx 'format: OBJ' <<<"$info" &&
  grep -qx 'bounds max: 0.5 0.5 0.5' <<<"$info"; then
  ok "info box.obj"
else
  bad "info box.obj" "$(tr '\n' ';' <<<"${info:-}") $(head -n 2 "$scratch/info.log")"
fi
if info=$("$facet" info "$stl_models/Spider_ascii.stl" 2>"$scratch/info_stl.log") &&
  grep -qx 'vertices: 722' <<<"$info" && grep -qx 'triangles: 1368' <<<"$info" &&
  grep -qx 'format: STL' <<<"$info"; then
  ok "info Spider_ascii.stl"
else
  bad "info Spider_ascii.stl" "$(tr '\n' ';' <<<"${info:-}") $(head -n 2 "$scratch/info_stl.log")"
fi
if info=$("$facet" info "$models/spider.obj" 2>/dev/null) && grep -qx 'materials: 5' <<<"$info" &&
  grep -qx 'triangles: [0-9]*' <<<"$info"; then
  ok "info spider.obj"
else
  bad "info spider.obj" "$(tr '\n' ';' <<<"${info:-}")"
fi

# Each reader names itself; glTF's textures are decoded with the model.
gltf=/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
if info=$("$facet" info "$gltf" 2>/dev/null) && grep -qx 'format: GLB' <<<"$info" &&
  grep -qx 'textured materials: 1' <<<"$info" && grep -qx 'triangles: 12' <<<"$info"; then
  ok "info BoxTextured.glb"
else
  bad "info BoxTextured.glb" "$(tr '\n' ';' <<<"${info:-}")"
fi
if info=$("$facet" info /usr/share/assimp/models/Collada/duck.dae 2>/dev/null) &&
  grep -qx 'format: Assimp (dae)' <<<"$info" && grep -qx 'triangles: 4212' <<<"$info"; then
  ok "info duck.dae"
else
  bad "info duck.dae" "$(tr '\n' ';' <<<"${info:-}")"
fi
run gltf_binary image 160 120 inside -- render "$gltf" --resolution 160,120
run collada image 160 120 inside -- render /usr/share/assimp/models/Collada/duck.dae --resolution 160,120
# Through the file's own perspective and orthographic cameras.
cameras=/usr/share/assimp/models/glTF2/cameras/Cameras.gltf
run camera_index_0 image 160 120 -- render "$cameras" --camera-index 0 --resolution 160,120
run camera_index_1 image 160 120 -- render "$cameras" --camera-index 1 --resolution 160,120

# A contact sheet: 5 views of 120x90 in 3 columns and 2 rows; each view's cell holds the model and its label, the
# views differ from each other, and the sixth cell is empty background.
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
if "$facet" render "$engine" --views front,top,iso,oblique,one-point --resolution 120,90 \
  --output "$scratch/sheet.png" 2>"$scratch/sheet.err"; then
  cat "$e2e_lib/png.py" - >"$scratch/sheet.py" <<'PY'
w, h, ch, rows = read_png(sys.argv[1])
assert (w, h) == (360, 180), (w, h)
background = tuple(rows[h - 1][(w - 1) * ch:(w - 1) * ch + 3])
def cell(k):
    x0, y0 = (k % 3) * 120, (k // 3) * 90
    return [tuple(rows[y][x * ch:x * ch + 3]) for y in range(y0, y0 + 90) for x in range(x0, x0 + 120)]
def drawn(pixels):
    return sum(1 for p in pixels[120 * 20:] if p != background)  # below the label strip
cells = [cell(k) for k in range(6)]
for k in range(5):
    assert drawn(cells[k]) > 500, f'view {k} shows {drawn(cells[k])} model pixels'
    label = cells[k][2 * 120:12 * 120]
    assert any(p == (255, 255, 255) for p in label), f'view {k} has no white label text'
for a in range(5):
    for b in range(a + 1, 5):
        assert cells[a] != cells[b], f'views {a} and {b} are the same picture'
assert all(p == background for p in cells[5]), 'the sixth cell is not empty'
PY
  if msg=$(python3 "$scratch/sheet.py" "$scratch/sheet.png" 2>&1); then ok "contact sheet of 5 views"; else bad "contact sheet" "$msg"; fi
else
  bad "contact sheet" "$(cat "$scratch/sheet.err")"
fi
# Under the sanitizers the animations and the thread-count renders draw one sample: four make the instrumented
# rasterizer several times slower, and the sanitized unit tests cover multisampling.
light=()
[ -n "${FACET_E2E_SANITIZED:-}" ] && light=(--samples 1)
# A turntable: an animated GIF of 36 frames that loops, with one palette of many colours; or numbered PNG frames.
if "$facet" render "$engine" "${light[@]}" --turntable 36 --resolution 96,72 --output "$scratch/turn.gif" 2>"$scratch/turn.err"; then
  if msg=$(python3 "$e2e_lib/gif.py" "$scratch/turn.gif" 96 72 36 8 2>&1); then  # 300 cs / 36 frames, rounded
    ok "turntable GIF: $msg"
  else
    bad "turntable GIF" "$msg"
  fi
else
  bad "turntable GIF" "$(cat "$scratch/turn.err")"
fi
if "$facet" render "$engine" "${light[@]}" --turntable 4 --resolution 96,72 --output "$scratch/turn_{frame:02}.png" 2>/dev/null &&
  [ "$(find "$scratch" -name 'turn_0[0-3].png' | wc -l)" = 4 ] && ! cmp -s "$scratch/turn_00.png" "$scratch/turn_01.png"
then
  ok "turntable PNG frames: turn_00.png to turn_03.png, each another view"
else
  bad "turntable PNG frames" "$(ls "$scratch" | grep turn_ | tr '\n' ' ')"
fi
# As H.264 in MP4 (36 frames in 3 s: 12 a second), whose first frame is the first PNG frame's view; as VP9 in WebM
# at an odd size, which 4:2:0 video pads to even.
if "$facet" render "$engine" "${light[@]}" --turntable 36 --resolution 96,72 --output "$scratch/turn.mp4" 2>"$scratch/turn.err" &&
  msg=$(python3 "$e2e_lib/video.py" "$scratch/turn.mp4" h264 96 72 36 12/1 "$scratch/turn_00.png" 2>&1); then
  ok "turntable MP4: $msg"
else
  bad "turntable MP4" "$(cat "$scratch/turn.err") ${msg:-}"
fi
if "$facet" render "$engine" --turntable 9 --resolution 45,33 --output "$scratch/turn.WebM" 2>"$scratch/turn.err" &&
  msg=$(python3 "$e2e_lib/video.py" "$scratch/turn.WebM" vp9 45 33 9 3/1 2>&1); then
  ok "turntable WebM: $msg"
else
  bad "turntable WebM" "$(cat "$scratch/turn.err") ${msg:-}"
fi
# Every output is the same bytes at any thread count: the image and every buffer, and a turntable as GIF and MP4.
same_at_any_thread_count=1
for t in 1 2 3; do
  mkdir -p "$scratch/threads$t"
  "$facet" render "$gltf" --threads "$t" --resolution 96,72 --output "$scratch/threads$t/c.png" \
    --output-depth "$scratch/threads$t/d.npy" --output-normal "$scratch/threads$t/n.exr" \
    --output-ids "$scratch/threads$t/i.npy" --output-mask "$scratch/threads$t/m.png" 2>/dev/null &&
    "$facet" render "$engine" "${light[@]}" --threads "$t" --turntable 6 --resolution 64,48 \
      --output "$scratch/threads$t/t.gif" &&
    "$facet" render "$engine" "${light[@]}" --threads "$t" --turntable 6 --resolution 64,48 \
      --output "$scratch/threads$t/t.mp4" ||
    same_at_any_thread_count=0
done 2>/dev/null
for t in 2 3; do
  for f in c.png d.npy n.exr i.npy m.png t.gif t.mp4; do
    cmp -s "$scratch/threads1/$f" "$scratch/threads$t/$f" || same_at_any_thread_count=0
  done
done
if [ "$same_at_any_thread_count" = 1 ]; then
  ok "PNG, .npy, .exr, mask, GIF and MP4 outputs are the same bytes at 1, 2 and 3 threads"
else
  bad "outputs at any thread count" "$(cd "$scratch" && md5sum threads*/* | sort)"
fi
for args in "--views front,bottom" "--views front --output-depth $scratch/d.npy" "--views front --camera-index 0" \
  "--turntable 8 --output-mask $scratch/m.png" "--turntable 4 --views front" "--turntable 0"; do
  # shellcheck disable=SC2086  # the cases are word lists
  out=$scratch/bad_sheet.png
  [[ $args == --turntable* ]] && out=$scratch/bad_turn.gif
  "$facet" render "$engine" $args --output "$out" 2>"$scratch/bad_sheet.err"
  status=$?
  if [ "$status" -eq 2 ] && [ ! -e "$out" ] && [ "$(wc -l <"$scratch/bad_sheet.err")" -eq 1 ]; then
    ok "refused: $args: $(cat "$scratch/bad_sheet.err")"
  else
    bad "refused: $args" "exit $status: $(cat "$scratch/bad_sheet.err")"
  fi
done

finish
