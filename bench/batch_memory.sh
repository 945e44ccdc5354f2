#!/usr/bin/env bash
# batch_memory.sh - a batch's peak memory against its job count: 1,000, 10,000 and 100,000 thumbnails of the
# batch benchmark's six real models (32x32, so that 100,000 render in a couple of minutes on two cores), each job
# at its own angle and writing its own file. Usage: bench/batch_memory.sh FACET [LARGEST]. Prints the peak resident
# memory of each batch, its time, and the memory each job added beyond the smallest batch.
set -euo pipefail
facet=$(realpath "$1")
largest=${2:-100000}
models=/usr/share/assimp/models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

make_jobs() {
  python3 - "$1" "$models" <<'PY'
import json, sys
n, root = int(sys.argv[1]), sys.argv[2]
models = ['OBJ/WusonOBJ.obj', 'OBJ/spider.obj', 'PLY/Wuson.ply', 'STL/Spider_binary.stl', 'Collada/duck.dae',
          'glTF2/BoxTextured-glTF-Binary/BoxTextured.glb']
for k in range(n):
    print(json.dumps({'model': f'{root}/{models[k % len(models)]}', 'output': f'out/{k // 1000:03}/{k:06}.png',
                      'resolution': [32, 32], 'camera-azimuth-angle': (k * 37) % 360,
                      'camera-elevation-angle': (k * 13) % 60 - 20}))
PY
}
printf '%8s %12s %10s %14s\n' jobs "peak (KiB)" "time (s)" "KiB per job"
base=
for n in 1000 10000 "$largest"; do
  make_jobs "$n" >jobs.jsonl
  rm -rf out
  start=$(date +%s.%N)
  kib=$(/usr/bin/time -f %M "$facet" batch jobs.jsonl --quiet 2>&1 >/dev/null | tail -n 1)
  seconds=$(echo "$(date +%s.%N) - $start" | bc -l)
  made=$(find out -name '*.png' | wc -l)
  [ "$made" = "$n" ] || { echo "batch_memory: $made of $n images made" >&2; exit 1; }
  [ -z "$base" ] && base=$kib
  printf '%8d %12d %10.1f %14.4f\n' "$n" "$kib" "$seconds" "$(echo "($kib - $base) / ($n - 999)" | bc -l)"
done
