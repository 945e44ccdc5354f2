#!/usr/bin/env bash
# cpu_levels.sh - `facet bench` at every CPU level this machine has (FACET_CPU) against the OpenGL reference (glref,
# llvmpipe at its default width) on the scenes of SCENES.md and a generated 200,704-triangle OBJ.
# Usage: bench/cpu_levels.sh FACET GLREF [ROUNDS] [extra bench flags...]   (default 3 rounds; 1920x1080, 2 threads)
# Each round runs glref once and facet once per level, in an order that rotates from round to round (the host is
# noisy); prints every round's median frame times, then per scene the medians and glref / facet per level.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,6p "$0" >&2; exit 2; }
facet=$(realpath "$1") glref=$(realpath "$2")
rounds=${3:-3}
shift $(($# >= 3 ? 3 : 2))
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$(dirname "$0")/make_spheres.py" "$work"

levels=()
for level in avx512 avx2 sse4 baseline; do
  got=$(FACET_CPU=$level "$facet" bench --sphere 8 --resolution 32,24 --frames 1 --warmup 0 --json |
    sed -n -E 's/.*"isa":"([a-z0-9]+)".*/\1/p')
  [ "$got" = "$level" ] && levels+=("$level")
done
scenes=("--sphere 224" "--sphere 707" "--sphere 1414" "--quads 64 --order b2f" "--quads 64 --order f2b"
        "--mesh /usr/share/assimp/models/OBJ/WusonOBJ.obj" "--mesh $work/sphere200k.obj")
programs=(glref "${levels[@]}")
ms() {  # ms PROGRAM SCENE-FLAGS...: the median frame time the program reports
  local program=$1
  shift
  if [ "$program" = glref ]; then "$glref" "$@" --json; else FACET_CPU=$program "$facet" bench "$@" --json; fi |
    sed -n -E 's/.*"median_ms":([0-9.]+).*/\1/p'
}
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "| scene | round | $(printf '%s (ms) | ' "${programs[@]}")"
declare -A times
for scene in "${scenes[@]}"; do
  for ((r = 0; r < rounds; r++)); do
    row=()
    for ((k = 0; k < ${#programs[@]}; ++k)); do
      p=${programs[$(((k + r) % ${#programs[@]}))]}
      # shellcheck disable=SC2086  # the scene flags are meant to split
      times[$p,$r]=$(ms "$p" $scene --threads 2 "$@")
    done
    for p in "${programs[@]}"; do row+=("${times[$p,$r]}"); done
    echo "| ${scene##*/} | $((r + 1)) | $(printf '%s | ' "${row[@]}")"
  done
  medians=()
  for p in "${programs[@]}"; do
    v=()
    for ((r = 0; r < rounds; r++)); do v+=("${times[$p,$r]}"); done
    medians+=("$(median "${v[@]}")")
  done
  ratios=()
  for ((k = 1; k < ${#programs[@]}; ++k)); do
    ratios+=("$(awk -v a="${medians[0]}" -v b="${medians[$k]}" 'BEGIN {printf "%.2fx", a / b}')")
  done
  echo "| ${scene##*/} | median | $(printf '%s | ' "${medians[@]}")glref / facet: ${ratios[*]} |"
done
