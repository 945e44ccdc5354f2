#!/usr/bin/env bash
# glref_cli.sh - the OpenGL reference (bench/glref) against `facet bench` through bench/compare_gl.sh: both draw the
# same scenes (docs/BENCHMARK.md) and their images agree; glref refuses bad arguments as the contract says.
# Usage: bash tests/e2e/glref_cli.sh <path-to-facet> <path-to-glref> <scratch-dir>
set -u
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"

facet=${1:?usage: glref_cli.sh <path-to-facet> <path-to-glref> <scratch-dir>}
glref=${2:?usage: glref_cli.sh <path-to-facet> <path-to-glref> <scratch-dir>}
scratch=${3:?usage: glref_cli.sh <path-to-facet> <path-to-glref> <scratch-dir>}
compare=$(dirname "${BASH_SOURCE[0]}")/../../bench/compare_gl.sh
rm -rf "$scratch"
mkdir -p "$scratch"

# agree NAME MAX_MEAN MIN_IOU FLAGS...: one round of compare_gl.sh; the images' mean difference and coverage IoU.
agree() {
  local name=$1 max_mean=$2 min_iou=$3 out
  shift 3
  if ! out=$(ROUNDS=1 bash "$compare" "$facet" "$glref" "$scratch/$name" "$@" --resolution 320,180 --threads 1 \
    --warmup 0 --frames 2 2>&1); then
    bad "$name" "compare_gl.sh failed: $out"
    return
  fi
  if python3 - "$name" "$max_mean" "$min_iou" "$(grep '^{' <<<"$out" | tail -n 1)" <<'PY'; then
import json, sys
name, max_mean, min_iou, line = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
d = json.loads(line)
problems = []
if d["mean_abs"] > max_mean: problems.append(f"mean_abs {d['mean_abs']} > {max_mean}")
if d["coverage_iou"] < min_iou: problems.append(f"coverage_iou {d['coverage_iou']} < {min_iou}")
if d["pixels"] != 320 * 180: problems.append(f"pixels {d['pixels']}")
if problems: print(name + ": " + "; ".join(problems)); sys.exit(1)
PY
    ok "$name: glref and facet agree"
  else
    bad "$name" "$out"
  fi
  grep -q "| median |" <<<"$out" || bad "$name" "no median row in: $out"
}

agree sphere 0.25 0.999 --sphere 64
agree sphere_4x 0.25 0.995 --sphere 64 --samples 4
agree quads 0.25 0.999 --quads 8 --order f2b
agree wuson 0.25 0.999 --mesh /usr/share/assimp/models/OBJ/WusonOBJ.obj

# The contract's argument errors: status 2, one line on stderr, nothing written.
for flags in "--sphere 2" "--sphere 8 --quads 4" "--sphere 8 --order f2b" "--sphere 8 --samples 3" "--sphere 8 --frobnicate 1" \
  "--mesh $scratch/missing.obj" "--sphere 8 --resolution 0,10"; do
  # shellcheck disable=SC2086  # the flags are meant to split
  "$glref" $flags --png "$scratch/bad.png" >"$scratch/bad.out" 2>"$scratch/bad.err"
  status=$?
  if [ "$status" -ne 2 ]; then
    bad "glref $flags" "status $status, expected 2"
  elif [ "$(wc -l <"$scratch/bad.err")" -ne 1 ]; then
    bad "glref $flags" "expected one line on stderr, got: $(cat "$scratch/bad.err")"
  elif [ -e "$scratch/bad.png" ]; then
    bad "glref $flags" "wrote an image"
  else
    ok "glref $flags: $(cat "$scratch/bad.err")"
  fi
done

finish
