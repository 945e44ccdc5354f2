#!/usr/bin/env bash
# viewer_cli.sh - `facet view` in a real X server (Xvfb): scripted runs, screenshots, what each toggle key changes.
# Usage: viewer_cli.sh FACET SCRATCH. Starts its own Xvfb through xvfb-run. Prints one line per case and a closing
# "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
mkdir -p "$scratch"
rm -rf "${scratch:?}"/*

if ! "$facet" view --help | grep -q "Keys:"; then
  bad "facet view" "this facet was built without SDL2"
  finish
  exit
fi
command -v xvfb-run >/dev/null || { bad "xvfb-run" "not installed (scripts/deps.sh installs xvfb)"; finish; exit; }

# shot NAME ARGS...: a scripted run at 320x240 writing $scratch/NAME.png; its exit status is the run's.
shot() {
  local name=$1
  shift
  xvfb-run -a -s "-screen 0 1280x1024x24" "$facet" view --resolution 320,240 --threads 2 \
    --screenshot "$scratch/$name.png" "$@" 2>"$scratch/$name.err"
}

# The torus a third of a second in (30 frames at 1/60 s), turned enough that it hides parts of itself.
torus=(--demo torus --frames 20)
for case in "default:" "wire:w" "edges:e" "nodepth:z" "cullback:c" "painter:p" "painter_shuffled:ps" \
  "nodepth_shuffled:zs" "flat:2" "normals:6" "ortho:o" "antialias:a" "paused: " "help:h" "colourmap:m" \
  "colourmap_off:mm"; do
  name=${case%%:*}
  keys=${case#*:}
  if shot "$name" "${torus[@]}" --keys "$keys"; then
    ok "--keys '$keys' ($name): exit 0, $(cat "$scratch/$name.err")"
  else
    bad "--keys '$keys' ($name)" "exit $?: $(cat "$scratch/$name.err")"
  fi
done

cat "$e2e_lib/png.py" - >"$scratch/check.py" <<'PY'
import sys
folder = sys.argv[1]
images = {}
def image(name):
    if name not in images:
        w, h, ch, rows = read_png(f'{folder}/{name}.png')
        images[name] = [tuple(row[i:i + 3]) for row in rows for i in range(0, w * ch, ch)]
    return images[name]
def covered(name):
    """Pixels that are not the demo's white background."""
    return sum(1 for p in image(name) if p != (255, 255, 255))
def changed(a, b):
    return sum(1 for p, q in zip(image(a), image(b)) if p != q)
results = []
def check(what, ok, detail):
    results.append(ok)
    print(('ok   ' if ok else 'FAIL ') + what + ': ' + detail)
total = 320 * 240
c = covered('default')
check('the torus draws', 0.1 * total < c < 0.9 * total and len(set(image('default'))) > 50,
      f'{c} of {total} pixels covered, {len(set(image("default")))} colours')
w = covered('wire')
check('w: wireframe covers fewer pixels', 0 < w < c, f'{w} against {c}')
for name, key in [('edges', 'e'), ('nodepth', 'z'), ('flat', '2'), ('normals', '6'), ('ortho', 'o'),
                  ('antialias', 'a'), ('help', 'h')]:
    n = changed('default', name)
    check(f'{key}: changes the picture', n > 100, f'{n} pixels differ')
n = changed('default', 'nodepth')
check('culling off, depth test off: the closed torus shows hidden faces', n > 100, f'{n} pixels differ')
n = changed('default', 'cullback')
check('c: culling back faces of a closed mesh under the depth test changes nothing', n == 0, f'{n} pixels differ')
n = changed('painter', 'painter_shuffled')
check('p + s: the painter\'s algorithm sorts a shuffled order back into the same picture', n == 0, f'{n} pixels differ')
n = changed('nodepth', 'nodepth_shuffled')
check('z + s: without a depth test the order shows', n > 100, f'{n} pixels differ')
n = changed('default', 'colourmap')
hues = len({(r // 32, g // 32, b // 32) for r, g, b in image('colourmap')}) - len({(r // 32, g // 32, b // 32) for r, g, b in image('default')})
check('m: the height colour map colours the torus', n > 1000 and hues > 5, f'{n} pixels differ, {hues} more hues')
n = changed('default', 'colourmap_off')
check('m twice: back to its own colours', n == 0, f'{n} pixels differ')
n = changed('default', 'paused')
check('space: paused at the start shows another moment', n > 100, f'{n} pixels differ')
print(f'{sum(results)} passed, {len(results) - sum(results)} failed')
sys.exit(0 if all(results) else 1)
PY
if python3 "$scratch/check.py" "$scratch" >"$scratch/check.out"; then
  while read -r line; do [[ $line == ok* ]] && ok "${line#ok   }"; done <"$scratch/check.out"
else
  while read -r line; do
    [[ $line == ok* ]] && ok "${line#ok   }"
    [[ $line == FAIL* ]] && bad "${line#FAIL }"
  done <"$scratch/check.out"
fi

# A model file, and the errors of a scripted run.
model=/usr/share/assimp/models/OBJ/WusonOBJ.obj
if shot wuson "$model" --frames 2 --keys 4; then ok "a model file: $(cat "$scratch/wuson.err")"; else bad "model" "$(cat "$scratch/wuson.err")"; fi
# The model's own look takes the lighting options: a key light with shadows and ambient occlusion changes it.
if shot wuson_own "$model" --frames 1 && shot wuson_lit "$model" --frames 1 --light-direction 0,1,0.3 --shadows \
  --ambient-occlusion && ! cmp -s "$scratch/wuson_own.png" "$scratch/wuson_lit.png"; then
  ok "--light-direction --shadows --ambient-occlusion change the model's own look"
else
  bad "lighting options" "$(cat "$scratch/wuson_lit.err")"
fi
# A model's animation plays, pauses (space) and steps a frame (. forward, , back): simple_skin paused at 0 s, stepped
# two frames on, and stepped one on and one back.
skin=/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf
if shot skin_paused "$skin" --frames 2 --keys " " && shot skin_stepped "$skin" --frames 2 --keys ".." &&
  shot skin_back "$skin" --frames 2 --keys ".,"; then
  # Compared as decoded pixels: PNG bytes need not repeat.
  same() { python3 -c "exec(open('$e2e_lib/png.py').read()); import sys; sys.exit(read_png('$1') != read_png('$2'))"; }
  if ! same "$scratch/skin_paused.png" "$scratch/skin_stepped.png" &&
    same "$scratch/skin_paused.png" "$scratch/skin_back.png"; then
    ok "a model's animation pauses and steps"
  else
    bad "animation steps" "stepped frames are not as expected"
  fi
else
  bad "animation steps" "$(cat "$scratch/skin_stepped.err")"
fi
# m steps through the colour maps a model can take: a scan with intensities takes height, then intensity (grey).
python3 -c '
for k in range(200):
    print(k / 100 - 1, (k % 10) / 50, 0, 20 + 3 * k)' >"$scratch/ramp.xyz"
if shot ramp_intensity "$scratch/ramp.xyz" --frames 1 --keys mm && shot ramp_own "$scratch/ramp.xyz" --frames 1 --keys mmm &&
  msg=$(cat "$e2e_lib/png.py" - <<'PY' | python3 - "$scratch/ramp_intensity.png" "$scratch/ramp_own.png" 2>&1
import sys
def pixels(path):
    w, h, ch, rows = read_png(path)
    return [tuple(row[i:i + 3]) for row in rows for i in range(0, w * ch, ch)]
mapped, own = pixels(sys.argv[1]), pixels(sys.argv[2])
changed = [p for p, q in zip(mapped, own) if p != q]
greys = sorted({p[0] for p in changed if p[0] == p[1] == p[2]})
assert len(changed) > 100 and len(greys) > 20, f"{len(changed)} pixels changed, {len(greys)} greys"
print(f"{len(changed)} pixels grey against m m m (no map), {greys[0]} to {greys[-1]}")
PY
); then
  ok "m m: a scan by intensity: $msg"
else
  bad "m m: a scan by intensity" "${msg:-$(cat "$scratch/ramp_intensity.err")}"
fi
expect_error() {
  local name=$1 status=$2
  shift 2
  xvfb-run -a -s "-screen 0 1280x1024x24" "$facet" view --frames 1 "$@" >/dev/null 2>"$scratch/$name.err"
  local got=$?
  if [ "$got" -eq "$status" ] && [ "$(wc -l <"$scratch/$name.err")" -eq 1 ] && grep -q "^facet: error: " "$scratch/$name.err"; then
    ok "$name: $(cat "$scratch/$name.err")"
  else
    bad "$name" "exit $got: $(cat "$scratch/$name.err")"
  fi
}
expect_error missing_model 1 "$scratch/none.obj"
expect_error model_and_demo 2 "$model" --demo cube
expect_error unknown_key 2 --demo cube --keys "wx"
expect_error screenshot_format 2 --demo cube --screenshot "$scratch/x.jpg"
expect_error missing_hdri 1 "$model" --hdri "$scratch/none.hdr"
# No display at all: a clean error, not a crash.
env -u DISPLAY -u WAYLAND_DISPLAY SDL_VIDEODRIVER=x11 "$facet" view --demo cube --frames 1 2>"$scratch/nodisplay.err"
status=$?
if [ "$status" -eq 1 ] && grep -q "^facet: error: cannot open a window" "$scratch/nodisplay.err"; then
  ok "no display: $(cat "$scratch/nodisplay.err")"
else
  bad "no display" "exit $status: $(cat "$scratch/nodisplay.err")"
fi
finish
