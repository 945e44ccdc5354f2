#!/usr/bin/env bash
# animation.sh - a clip rendered to video as users render it: `facet render --animate`, a whole process, on the
# skinned tube of bench/make_animated.py (12,800 vertices in 8 bones, 25,472 triangles), 120 frames of 640x480 at
# 30 a second (4 s of video) into H.264 MP4, 4 samples, 2 threads; and how many times faster than real time it is.
# Usage: bench/animation.sh FACET [ROUNDS]   (default 5; prints every round and the median)
set -euo pipefail
[ $# -ge 1 ] || { sed -n 2,5p "$0" >&2; exit 2; }
facet=$(realpath "$1")
rounds=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$(dirname "$0")/make_animated.py" "$work/tube.glb"
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
run() {
  local start end
  start=$(date +%s%N)
  "$facet" render "$work/tube.glb" --animate --frames 120 --fps 30 --resolution 640,480 --threads 2 \
    --output "$work/clip.mp4"
  end=$(date +%s%N)
  echo $(((end - start) / 1000000))
}
run >/dev/null  # the page cache and the dynamic loader warmed once
times=()
for r in $(seq "$rounds"); do
  t=$(run)
  times+=("$t")
  echo "round $r: $t ms"
done
m=$(printf '%s\n' "${times[@]}" | median)
awk -v m="$m" 'BEGIN {printf "median %.0f ms for 4 s of video: %.1fx real time\n", m, 4000 / m}'
