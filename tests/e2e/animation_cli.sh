#!/usr/bin/env bash
# animation_cli.sh - a model's animations through the CLI: info lists them, --time poses, --animate plays, errors.
# Usage: animation_cli.sh FACET SCRATCH. Prints one line per check and a closing "N passed, M failed".
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
mkdir -p "$scratch"
rm -rf "${scratch:?}"/*
models=/usr/share/assimp/models/glTF2
skin=$models/simple_skin/simple_skin.gltf
cube=$models/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf
still=$models/BoxTextured-glTF/BoxTextured.gltf

check=$scratch/check.py
cat "$e2e_lib/png.py" - >"$check" <<'EOF'

cmd = sys.argv[1]
if cmd == 'same':  # same A B: identical images
    if read_png(sys.argv[2]) != read_png(sys.argv[3]):
        sys.exit('images differ')
    print('identical images')
elif cmd == 'differ':  # differ A B
    if read_png(sys.argv[2]) == read_png(sys.argv[3]):
        sys.exit('identical images')
    print('images differ')
EOF
verify() {
  local name=$1; shift
  local result
  if result=$(python3 "$check" "$@" 2>&1); then ok "$name: $result"; else bad "$name" "$result"; fi
}
# render NAME MODEL FLAGS...: facet render MODEL FLAGS --output $scratch/NAME.png at 160x120; 0 when it succeeded.
render() {
  local name=$1 model=$2; shift 2
  if ! "$facet" render "$model" --resolution 160,120 "$@" --output "$scratch/$name.png" 2>"$scratch/$name.log"; then
    bad "$name" "facet render $* failed: $(head -n 2 "$scratch/$name.log")"
    return 1
  fi
}
# refused NAME STATUS TEXT ARGS...: facet ARGS exits with STATUS, says TEXT on stderr, and writes nothing.
refused() {
  local name=$1 status=$2 text=$3; shift 3
  rm -f "$scratch/refused.png" "$scratch"/refused_*
  "$facet" "$@" 2>"$scratch/$name.log" >/dev/null
  local got=$?
  if [ "$got" -eq "$status" ] && grep -qF -- "$text" "$scratch/$name.log" &&
    [ -z "$(ls "$scratch" | grep '^refused')" ]; then
    ok "$name: exit $got, $(head -n 1 "$scratch/$name.log")"
  else
    bad "$name" "exit $got, $(head -n 1 "$scratch/$name.log")"
  fi
}

# facet info lists each animation with its length and channels.
if out=$("$facet" info "$cube" 2>&1) && grep -qx 'animations: 1' <<<"$out" &&
  grep -qx 'animation 0: "Square", 4.2 s, 1 channel (weights 1)' <<<"$out" &&
  grep -qx 'morph targets: 2' <<<"$out"; then
  ok "info lists the morph cube's animation"
else
  bad "info of the morph cube" "$(grep -i anim <<<"$out")"
fi
if out=$("$facet" info "$skin" 2>&1) && grep -qx 'skins: 1' <<<"$out" &&
  grep -qx 'animation 0: "", 5.5 s, 1 channel (rotation 1)' <<<"$out"; then
  ok "info lists the skin's animation"
else
  bad "info of simple_skin" "$(grep -iE 'anim|skin' <<<"$out")"
fi

# --time poses: the skin at rest, at 1.25 s (by default the first animation, by index and by name alike).
render skin_rest "$skin" && render skin_t "$skin" --time 1.25 && render skin_index "$skin" --time 1.25 --animation 0 &&
  render cube_rest "$cube" && render cube_t "$cube" --time 1 && render cube_name "$cube" --time 1 --animation Square &&
  {
    verify skin_moves differ "$scratch/skin_rest.png" "$scratch/skin_t.png"
    verify skin_by_index same "$scratch/skin_t.png" "$scratch/skin_index.png"
    verify cube_morphs differ "$scratch/cube_rest.png" "$scratch/cube_t.png"
    verify cube_by_name same "$scratch/cube_t.png" "$scratch/cube_name.png"
  }
# A time past the clip's end draws its end, with a warning.
if render skin_late "$skin" --time 99 && render skin_end "$skin" --time 5.5; then
  verify time_clamped same "$scratch/skin_late.png" "$scratch/skin_end.png"
  if grep -q "99 s lies outside the animation (0 to 5.5 s); drawing 5.5 s" "$scratch/skin_late.log"; then
    ok "a late time warns: $(head -n 1 "$scratch/skin_late.log")"
  else
    bad "late time warning" "$(head -n 1 "$scratch/skin_late.log")"
  fi
fi

# --animate: the clip to its end at --fps, as one GIF (4.2 s at 10 a second: 42 frames of 10 cs).
if "$facet" render "$cube" --animate --fps 10 --resolution 80,60 --output "$scratch/cube.gif" 2>"$scratch/gif.log" &&
  msg=$(python3 "$e2e_lib/gif.py" "$scratch/cube.gif" 80 60 42 10 2>&1); then
  ok "the clip as a GIF: $msg"
else
  bad "the clip as a GIF" "$(head -n 2 "$scratch/gif.log") ${msg:-}"
fi
# ... or as numbered PNGs, --frames of them from --time, each the still at its moment (through one fixed camera: a
# clip is framed by all its moments, a still by its own).
camera=(--camera-position 0.5,1,6 --camera-focal-point 0.5,1,0 --near 1 --far 20 --color 0.9,0.3,0.2)
if "$facet" render "$skin" --animate --fps 10 --frames 3 --time 2 --resolution 160,120 "${camera[@]}" \
  --output "$scratch/skin_{frame}.png" 2>"$scratch/frames.log"; then
  files=$(cd "$scratch" && ls skin_[0-9].png | tr '\n' ' ')
  if [ "$files" = "skin_0.png skin_1.png skin_2.png " ]; then ok "frames: $files"; else bad frames "wrote: $files"; fi
  render skin_2_1 "$skin" --time 2.1 "${camera[@]}" &&
    verify frame_is_the_still same "$scratch/skin_1.png" "$scratch/skin_2_1.png"
  render skin_2 "$skin" --time 2 "${camera[@]}" &&
    verify first_frame_is_the_still same "$scratch/skin_0.png" "$scratch/skin_2.png"
else
  bad frames "$(head -n 2 "$scratch/frames.log")"
fi
# With a turntable: its frames turn the camera once round while the clip plays.
if "$facet" render "$cube" --animate --turntable 4 --resolution 80,60 --output "$scratch/turn_{frame}.png" \
  2>"$scratch/turn.log" && [ -f "$scratch/turn_3.png" ] && [ ! -f "$scratch/turn_4.png" ]; then
  ok "an animated turntable of 4 frames"
else
  bad "animated turntable" "$(head -n 2 "$scratch/turn.log")"
fi
# Motion to the next frame beside each numbered frame, as .npy and .exr: H x W x 2 floats, some of them moving.
if "$facet" render "$skin" --animate --frames 2 --time 0.6 --resolution 64,48 --output "$scratch/flow_{frame}.png" \
  --output-motion "$scratch/flow_{frame}.npy" 2>"$scratch/flow.log" &&
  "$facet" render "$skin" --time 0.6 --resolution 64,48 --output "$scratch/flow.png" \
    --output-motion "$scratch/flow.exr" 2>>"$scratch/flow.log" &&
  msg=$(python3 - "$scratch" <<'PY' 2>&1
import struct, sys
d = sys.argv[1]
for name in ("flow_0.npy", "flow_1.npy"):
    data = open(f"{d}/{name}", "rb").read()
    length = int.from_bytes(data[8:10], "little")
    header = data[10:10 + length].decode()
    assert "'shape': (48, 64, 2)" in header and "<f4" in header, header
    values = struct.unpack(f"<{48 * 64 * 2}f", data[10 + length:])
    moving = sum(1 for i in range(0, len(values), 2) if abs(values[i]) + abs(values[i + 1]) > 0.05)
    assert moving > 10, f"{name}: {moving} moving pixels"
exr = open(f"{d}/flow.exr", "rb").read()
assert exr[:4] == b"\x76\x2f\x31\x01" and b"R\0" in exr and b"G\0" in exr and b"B\0" not in exr[:400], "not a 2-channel EXR"
print(f"{moving} moving pixels, and a 2-channel EXR")
PY
  ); then
  ok "motion: $msg"
else
  bad motion "$(head -n 2 "$scratch/flow.log") ${msg:-}"
fi
# A batch job takes the same keys.
printf '{"model": "%s", "time": 1.25, "resolution": "160,120", "output": "%s"}\n' "$skin" "$scratch/batch_t.png" \
  >"$scratch/jobs.jsonl"
if "$facet" batch "$scratch/jobs.jsonl" --quiet 2>"$scratch/batch.log"; then
  verify batch_time same "$scratch/skin_t.png" "$scratch/batch_t.png"
else
  bad batch "$(head -n 2 "$scratch/batch.log")"
fi

# Refusals: one line naming the file or the flag, nothing written.
refused no_such_animation 1 "has no animation 'Walk' (it has 'Square')" \
  render "$cube" --animation Walk --output "$scratch/refused.png"
refused nothing_to_play 1 "has no animation to play" render "$still" --time 1 --output "$scratch/refused.png"
refused bad_fps 2 "--fps" render "$skin" --animate --fps 0 --output "$scratch/refused_{frame}.png"
refused bad_time 2 "--time" render "$skin" --time nan --output "$scratch/refused.png"
refused unnumbered 2 "{frame}" render "$skin" --animate --output "$scratch/refused.png"
refused turntable_motion 2 "colour output alone" \
  render "$skin" --turntable 3 --output "$scratch/refused.gif" --output-motion "$scratch/refused.npy"
refused video_of_depth 2 "colour output alone" \
  render "$skin" --animate --output "$scratch/refused.gif" --output-depth "$scratch/refused.npy"

finish
