#!/usr/bin/env bash
# batch_bench.sh - thumbnails as users make them: one `facet batch` process against one `facet render` per image.
# Usage: bench/batch_bench.sh FACET [ROUNDS] [JOBS]. Renders JOBS (600) thumbnails of 256x256 from six small real
# models of Debian's assimp-testmodels (OBJ with textures, PLY, STL, Collada, glTF), each at its own camera angle,
# both ways, alternating the two in every round (the host is noisy), and prints each round, the medians and the
# thumbnails a second. bench/batch_memory.sh measures the batch's memory against its job count.
set -euo pipefail
facet=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
rounds=${2:-3}
jobs=${3:-600}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

python3 "$here/thumbnail_jobs.py" "$jobs" 256 >jobs.jsonl
# The same jobs as command lines, run two at a time (one per core), as a shell loop with xargs -P would.
python3 - jobs.jsonl "$facet" >commands.txt <<'PY'
import json, shlex, sys
for line in open(sys.argv[1]):
    j = json.loads(line)
    print(' '.join(shlex.quote(a) for a in [sys.argv[2], 'render', j['model'], '--output', j['output'], '--threads',
          '1', '--resolution', '256,256', '--camera-azimuth-angle', str(j['camera-azimuth-angle']),
          '--camera-elevation-angle', str(j['camera-elevation-angle'])]))
PY

seconds() { local start end; start=$(date +%s.%N); "$@"; end=$(date +%s.%N); echo "$end - $start" | bc -l; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
batch_times=() process_times=()
printf '%-6s %12s %14s\n' round "batch (s)" "processes (s)"
for r in $(seq "$rounds"); do
  rm -rf out
  b=$(seconds "$facet" batch jobs.jsonl --quiet 2>/dev/null)
  [ "$(find out -name '*.png' | wc -l)" = "$jobs" ] || { echo "batch_bench: the batch made too few images" >&2; exit 1; }
  rm -rf out && mkdir -p out
  p=$(seconds xargs -P 2 -I{} sh -c '{} 2>/dev/null' <commands.txt)
  [ "$(find out -name '*.png' | wc -l)" = "$jobs" ] || { echo "batch_bench: the processes made too few images" >&2; exit 1; }
  batch_times+=("$b") process_times+=("$p")
  printf '%-6s %12.2f %14.2f\n' "$r" "$b" "$p"
done
mb=$(printf '%s\n' "${batch_times[@]}" | median)
mp=$(printf '%s\n' "${process_times[@]}" | median)
printf 'median: facet batch %.2f s (%.0f thumbnails/s); one process each %.2f s (%.0f/s); batch %.1fx faster\n' \
  "$mb" "$(echo "$jobs / $mb" | bc -l)" "$mp" "$(echo "$jobs / $mp" | bc -l)" "$(echo "$mp / $mb" | bc -l)"
