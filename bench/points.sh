#!/usr/bin/env bash
# points.sh - a frame of a 1-million-point coloured cloud (binary PLY, points on the unit sphere in random order,
# drawn as facet render's default 2-pixel squares) against a frame of sphere:707 (998,284 triangles), in alternated
# rounds: the cloud as `facet bench` draws a file (its points in the file's order) and as `facet render` draws it
# (the scene layer, which puts a cloud's points in spatial order; build/bench/facet_look_bench, 1 sample).
# Usage: bench/points.sh FACET [ROUNDS]   (default 5; 1920x1080, 2 threads; prints every round, the medians, the ratios)
set -euo pipefail
[ $# -ge 1 ] || { sed -n 2,4p "$0" >&2; exit 2; }
facet=$(realpath "$1")
rounds=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work/cloud1m.ply" <<'PY'
import math, random, struct, sys
random.seed(2)
n = 1000000
rows = bytearray()
for _ in range(n):
    z = random.uniform(-1, 1); t = random.uniform(0, 2 * math.pi); r = math.sqrt(1 - z * z)
    rows += struct.pack('<3f3B', r * math.cos(t), r * math.sin(t), z, int(255 * (z + 1) / 2), 128, 200)
with open(sys.argv[1], 'wb') as out:
    out.write((f'ply\nformat binary_little_endian 1.0\nelement vertex {n}\nproperty float x\nproperty float y\n'
               'property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n').encode())
    out.write(rows)
PY
ms() { "$facet" bench "$@" --threads 2 --json | sed -n -E 's/.*"median_ms":([0-9.]+).*/\1/p'; }
look_bench=$(dirname "$facet")/../bench/facet_look_bench
# The scene layer's frame: the first look's median (a cloud without normals is drawn unlit in every look).
scene_ms() { "$look_bench" "$work/cloud1m.ply" 1920 1080 1 2 3 10 | awk 'NR == 1 {print $2}'; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
p=() q=() s=()
echo "| round | 1M points, file order (ms) | 1M points, scene layer (ms) | sphere:707 (ms) |"
for ((r = 1; r <= rounds; r++)); do
  if ((r % 2)); then a=$(ms --mesh "$work/cloud1m.ply"); c=$(scene_ms); b=$(ms --sphere 707)
  else b=$(ms --sphere 707); c=$(scene_ms); a=$(ms --mesh "$work/cloud1m.ply"); fi
  p+=("$a") q+=("$c") s+=("$b")
  echo "| $r | $a | $c | $b |"
done
mp=$(printf '%s\n' "${p[@]}" | median) mq=$(printf '%s\n' "${q[@]}" | median)
msph=$(printf '%s\n' "${s[@]}" | median)
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a / b}'; }
echo "| median | $mp | $mq | $msph |"
echo "points / sphere: file order $(ratio "$mp" "$msph"), scene layer $(ratio "$mq" "$msph")"
