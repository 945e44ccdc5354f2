#!/usr/bin/env bash
# demo_cli.sh - `facet demo`: every demo scene renders, --time animates, --frames writes numbered PNGs.
# Usage: demo_cli.sh FACET SCRATCH. Prints one line per check and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
mkdir -p "$scratch"
rm -f "$scratch"/*.png "$scratch"/*.npy

# PNG checks: the shared reader (lib/png.py) followed by this script's commands.
check=$scratch/check.py
cat "$e2e_lib/png.py" - >"$check" <<'EOF'

def mask(path, bg):
    w, h, ch, rows = read_png(path)
    return w, h, [[any(abs(rows[y][x * ch + k] - bg[k]) > 2 for k in range(3)) for x in range(w)] for y in range(h)]

cmd = sys.argv[1]
if cmd == 'image':  # image FILE W H: the size, and 1%..99% of the pixels differ from the white background
    w, h, m = mask(sys.argv[2], (255, 255, 255))
    frac = sum(map(sum, m)) / (w * h)
    if (w, h) != (int(sys.argv[3]), int(sys.argv[4])) or not 0.01 <= frac <= 0.99:
        sys.exit(f'{w}x{h}, {frac:.1%} drawn')
    print(f'{w}x{h}, {frac:.1%} drawn')
elif cmd == 'differ':  # differ A B: the two images are not identical
    a, b = read_png(sys.argv[2]), read_png(sys.argv[3])
    if a == b:
        sys.exit('identical images')
    print('images differ')
elif cmd == 'same':  # same A B
    if read_png(sys.argv[2]) != read_png(sys.argv[3]):
        sys.exit('images differ')
    print('identical images')
elif cmd == 'apex-up':  # apex-up FILE: a shape narrow at the top and wide at the bottom (the upright pentagon)
    w, h, m = mask(sys.argv[2], (255, 255, 255))
    ys = [y for y in range(h) if any(m[y])]
    top, bottom = sum(m[ys[0] + 2]), sum(m[ys[-1] - 2])
    if not top < bottom:
        sys.exit(f'{top} px near the top row, {bottom} near the bottom')
    print(f'apex up ({top} px near the top, {bottom} near the bottom)')
elif cmd == 'pixel':  # pixel FILE X Y R G B: one pixel's colour within 8 levels
    w, h, ch, rows = read_png(sys.argv[2])
    x, y = int(sys.argv[3]), int(sys.argv[4])
    got = tuple(rows[y][x * ch:x * ch + 3])
    want = tuple(int(v) for v in sys.argv[5:8])
    if any(abs(g - e) > 8 for g, e in zip(got, want)):
        sys.exit(f'pixel ({x}, {y}) is {got}, expected {want}')
    print(f'pixel ({x}, {y}) is {got}')
EOF

# render NAME FACET-ARGS...: facet demo ... --output $scratch/NAME.png; 0 when it succeeded.
render() {
  local name=$1; shift
  if ! "$facet" demo "$@" --output "$scratch/$name.png" 2>"$scratch/$name.log"; then
    bad "$name" "facet demo $* failed: $(head -n 2 "$scratch/$name.log")"
    return 1
  fi
}
# verify NAME CHECK ARGS...: runs check.py and reports.
verify() {
  local name=$1; shift
  local result
  if result=$(python3 "$check" "$@" 2>&1); then ok "$name: $result"; else bad "$name" "$result"; fi
}

for demo in cube torus two-cubes pentagon; do
  render "$demo" "$demo" --resolution 200,150 && verify "$demo" image "$scratch/$demo.png" 200 150
done
render default_size cube && verify default_size image "$scratch/default_size.png" 800 800

# The rotating cube at t = 0 shows only its front face, red, filling the middle of the view.
render cube_t0 cube --time 0 --resolution 100,100 && verify cube_t0 pixel "$scratch/cube_t0.png" 50 50 255 0 0
render cube_t2 cube --time 2 --resolution 200,150 &&
  verify cube_animates differ "$scratch/cube.png" "$scratch/cube_t2.png"
render torus_t2 torus --time 2 --resolution 200,150 &&
  verify torus_animates differ "$scratch/torus.png" "$scratch/torus_t2.png"
# A demo takes the height colour map as a model does.
render torus_height torus --color-map height --resolution 200,150 &&
  verify torus_color_map differ "$scratch/torus.png" "$scratch/torus_height.png"
# The pentagon is upright at whole seconds: apex at the top (also checks the image is not upside down).
verify pentagon_upright apex-up "$scratch/pentagon.png"

# Drawing modes the "Computer Graphics from Scratch" demo toggles.
for flags in "--painter" "--no-depth-test --culling none" "--edges" "--wireframe" "--shading flat" \
  "--background-color 0,0,0 --color 0.2,0.6,1"; do
  name=two_cubes_$(tr -c 'a-z0-9\n' '_' <<<"${flags//--/}")
  # shellcheck disable=SC2086  # the flags are meant to split into words
  render "$name" two-cubes $flags --resolution 160,120 && ok "$name renders"
done

# --frames with {frame:04}: exactly the numbered files, 1/30 s apart (so consecutive cube frames differ).
rm -f "$scratch"/anim_*.png
if "$facet" demo cube --frames 3 --resolution 64,64 --output "$scratch/anim_{frame:04}.png" 2>"$scratch/anim.log"; then
  files=$(cd "$scratch" && ls anim_*.png | tr '\n' ' ')
  if [ "$files" = "anim_0000.png anim_0001.png anim_0002.png " ]; then
    ok "frames: $files"
    verify frames_differ differ "$scratch/anim_0000.png" "$scratch/anim_0001.png"
  else
    bad frames "wrote: $files"
  fi
  # Frame 0 starts at --time (default 1 s).
  render frame_start cube --resolution 64,64 --time 1 && verify frame_start same "$scratch/anim_0000.png" \
    "$scratch/frame_start.png"
else
  bad frames "$(head -n 2 "$scratch/anim.log")"
fi
rm -f "$scratch"/plain_*.png
if "$facet" demo pentagon --frames 2 --time 0.5 --resolution 48,48 --output "$scratch/plain_{frame}.png" \
  --output-depth "$scratch/plain_{frame}.npy" 2>"$scratch/plain.log" &&
  [ -f "$scratch/plain_0.png" ] && [ -f "$scratch/plain_1.png" ] && [ -f "$scratch/plain_1.npy" ]; then
  ok "frames with {frame} and depth"
else
  bad "frames with {frame}" "$(head -n 2 "$scratch/plain.log")"
fi
# --frames without a {frame} pattern would overwrite one file: a usage error that writes nothing.
rm -f "$scratch/frames.png"
"$facet" demo cube --frames 3 --resolution 64,64 --output "$scratch/frames.png" 2>/dev/null
status=$?
if [ "$status" -eq 2 ] && [ ! -e "$scratch/frames.png" ]; then ok "frames without a pattern: exit 2, nothing written"
else bad frames_without_pattern "exit $status$([ -e "$scratch/frames.png" ] && echo ', wrote frames.png')"; fi
# An animation written as one GIF: 30 frames 1/30 s apart, looping, one palette.
if "$facet" demo torus --frames 30 --resolution 80,80 --output "$scratch/torus.gif" 2>"$scratch/gif.log" &&
  msg=$(python3 "$e2e_lib/gif.py" "$scratch/torus.gif" 80 80 30 3 2>&1); then
  ok "demo as a GIF: $msg"
else
  bad "demo as a GIF" "$(head -n 2 "$scratch/gif.log") ${msg:-}"
fi
# And as a video: 30 frames at 30 a second, the first one the demo's still at the same moment.
if "$facet" demo torus --resolution 80,80 --output "$scratch/torus_still.png" 2>"$scratch/video.log" &&
  "$facet" demo torus --frames 30 --resolution 80,80 --output "$scratch/torus.webm" 2>>"$scratch/video.log" &&
  msg=$(python3 "$e2e_lib/video.py" "$scratch/torus.webm" vp9 80 80 30 30/1 "$scratch/torus_still.png" 2>&1); then
  ok "demo as WebM: $msg"
else
  bad "demo as WebM" "$(head -n 2 "$scratch/video.log") ${msg:-}"
fi

finish
