#!/usr/bin/env bash
# batch_memory.sh - a long batch keeps memory flat: 3,000 jobs peak within 25% of 300 jobs of the same models.
# Usage: batch_memory.sh FACET SCRATCH. Runs in the plain build only: a sanitizer's allocator keeps freed memory
# in quarantine on purpose, which says nothing about facet's.
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
mkdir -p "$scratch"
rm -rf "${scratch:?}"/*
cd "$scratch" || exit 1

# N jobs cycling through four small real models of four formats (one textured), each at its own camera angle.
make_jobs() {
  python3 - "$1" <<'PY'
import json, sys
root = '/usr/share/assimp/models'
models = ['OBJ/WusonOBJ.obj', 'PLY/Wuson.ply', 'STL/Spider_binary.stl', 'glTF2/BoxTextured-glTF-Binary/BoxTextured.glb']
for k in range(int(sys.argv[1])):
    print(json.dumps({'model': f'{root}/{models[k % 4]}', 'output': f'out/{k:05}.png', 'resolution': [64, 64],
                      'camera-azimuth-angle': (k * 37) % 360, 'camera-elevation-angle': (k * 13) % 60 - 20}))
PY
}
# The peak resident memory of one batch, in KiB, after checking it made every image.
peak() {
  make_jobs "$1" >"jobs$1.jsonl"
  rm -rf out
  local kib
  kib=$(/usr/bin/time -f %M "$facet" batch "jobs$1.jsonl" --quiet 2>&1 >/dev/null | tail -n 1)
  [ "$(find out -name '*.png' | wc -l)" = "$1" ] || kib="missing images"
  echo "$kib"
}
# The lowest of three runs each: which worker thread's allocator arena serves a job varies from run to run, and
# moves a batch's peak by a megabyte or two.
# A run that did not make every image is reported, whichever it was.
lower() {
  if [[ ! $1 =~ ^[0-9]+$ ]]; then echo "$1"
  elif [[ ! $2 =~ ^[0-9]+$ ]]; then echo "$2"
  else echo $(($1 < $2 ? $1 : $2)); fi
}
short=$(lower "$(lower "$(peak 300)" "$(peak 300)")" "$(peak 300)")
long=$(lower "$(lower "$(peak 3000)" "$(peak 3000)")" "$(peak 3000)")
# 25%: on a busy machine the arenas alone move the peak by up to 2.5 MiB (15% of it), while anything a job leaks
# grows with the 2,700 extra jobs: its smallest buffer, the 64x64 image (16 KiB), would add 40 MiB.
if [[ $short =~ ^[0-9]+$ && $long =~ ^[0-9]+$ ]] && [ $((long * 4)) -le $((short * 5)) ]; then
  ok "peak memory: 300 jobs $short KiB, 3000 jobs $long KiB"
else
  bad "peak memory" "300 jobs: $short KiB, 3000 jobs: $long KiB (more than 25% apart)"
fi

finish
