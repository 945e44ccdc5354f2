#!/usr/bin/env bash
# splats.sh - whole `facet render` processes of a 1-million-Gaussian scene (degree-3 harmonics, sampled on WusonOBJ's
# surface by make_splats.py) at 1920x1080 on 2 threads, with --timings: load, draw (projection, sort and blending)
# and the whole process, per round, then the medians.
# Usage: bench/splats.sh FACET [ROUNDS] [GAUSSIANS]   (default 5 rounds, 1,000,000 Gaussians)
set -euo pipefail
[ $# -ge 1 ] || { sed -n 2,5p "$0" >&2; exit 2; }
facet=$(realpath "$1")
rounds=${2:-5} gaussians=${3:-1000000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$(dirname "$0")/make_splats.py" /usr/share/assimp/models/OBJ/WusonOBJ.obj "$gaussians" \
  "$work/scene.ply"
"$facet" render "$work/scene.ply" --resolution 320,240 --output "$work/warm.png"  # the file into the page cache
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
loads=() draws=() totals=() peaks=()
echo "| round | load ms | draw ms | total ms | peak MiB |"
for ((r = 1; r <= rounds; r++)); do
  line=$("$facet" render "$work/scene.ply" --resolution 1920,1080 --threads 2 --timings \
    --output "$work/scene.png" 2>&1 | grep 'timings:')
  field() { sed -n -E "s/.*$1 ([0-9.]+).*/\\1/p" <<<"$line"; }
  loads+=("$(field load)") draws+=("$(field draw)") totals+=("$(field total)") peaks+=("$(field 'peak memory')")
  echo "| $r | ${loads[-1]} | ${draws[-1]} | ${totals[-1]} | ${peaks[-1]} |"
done
echo "| median | $(printf '%s\n' "${loads[@]}" | median) | $(printf '%s\n' "${draws[@]}" | median) |" \
  "$(printf '%s\n' "${totals[@]}" | median) | $(printf '%s\n' "${peaks[@]}" | median) |"
echo "scene file: $(stat -c %s "$work/scene.ply") bytes"
