#!/usr/bin/env bash
# compare_gl.sh - times `facet bench` against the OpenGL reference (glref) on one scene in alternating rounds, then
# compares their frame-0 images (docs/BENCHMARK.md).
# Usage: bench/compare_gl.sh FACET GLREF OUTDIR [scene flags...]   e.g. bench/compare_gl.sh build/tools/facet
#        build/bench/glref /tmp/gl --sphere 707 --threads 2. ROUNDS (default 3) pairs of runs; the two programs swap
#        order every round. stderr of every run goes to OUTDIR/compare.log.
set -euo pipefail
[ $# -ge 3 ] || { sed -n 2,6p "$0" >&2; exit 2; }
facet=$1 glref=$2 out=$3
shift 3
rounds=${ROUNDS:-3}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "compare_gl.sh: ROUNDS must be a positive integer, got '$rounds'" >&2; exit 2; }
mkdir -p "$out"
log=$out/compare.log
: >"$log"

result() {  # result NAME CMD...: the JSON result line the command prints
  local name=$1 stdout
  shift
  echo "== $name: $*" >>"$log"
  stdout=$("$@" --json 2>>"$log") || { echo "compare_gl.sh: $name failed: $*" >&2; tail -n 3 "$log" >&2; exit 1; }
  grep -m1 '^{' <<<"$stdout" || { echo "compare_gl.sh: $name printed no result line" >&2; exit 1; }
}
field() { sed -n -E "s/.*\"$1\":(\"([^\"]*)\"|([-+0-9.eE]+)).*/\2\3/p" <<<"$2"; }
median() { printf '%s\n' "$@" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

g_ms=() f_ms=() ratios=()
for ((r = 1; r <= rounds; r++)); do
  if ((r % 2)); then
    g=$(result glref "$glref" "$@"); f=$(result facet "$facet" bench "$@")
  else
    f=$(result facet "$facet" bench "$@"); g=$(result glref "$glref" "$@")
  fi
  if ((r == 1)); then
    scene=$(field scene "$g")
    for k in scene triangles width height warmup frames threads; do
      [ "$(field $k "$g")" = "$(field $k "$f")" ] ||
        echo "compare_gl.sh: warning: $k differs: glref $(field $k "$g"), facet $(field $k "$f")" >&2
    done
    echo "glref: $(field renderer "$g"); facet: $(field renderer "$f")"
    echo "| scene | round | glref ms | facet ms | glref/facet |"
    echo "|---|---|---:|---:|---:|"
  fi
  gm=$(field median_ms "$g") fm=$(field median_ms "$f")
  g_ms+=("$gm") f_ms+=("$fm") ratios+=("$(awk -v a="$gm" -v b="$fm" 'BEGIN {printf "%.3f", a / b}')")
  echo "| $scene | $r | $gm | $fm | ${ratios[-1]} |"
done
echo "| $scene | median | $(median "${g_ms[@]}") | $(median "${f_ms[@]}") | $(median "${ratios[@]}") |"

tag=${scene//[^A-Za-z0-9._-]/_}
"$glref" "$@" --warmup 0 --frames 1 --png "$out/$tag.glref.png" >/dev/null 2>>"$log"
"$facet" bench "$@" --warmup 0 --frames 1 --png "$out/$tag.facet.png" >/dev/null 2>>"$log"
echo "images $out/$tag.{glref,facet}.png, difference $out/$tag.diff.png:"
# The system python3, which has NumPy (a version manager's python3 earlier on PATH may not).
python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3
"$python" "$(dirname "${BASH_SOURCE[0]}")/glref/imgdiff.py" "$out/$tag.glref.png" "$out/$tag.facet.png" \
  --diff "$out/$tag.diff.png"
