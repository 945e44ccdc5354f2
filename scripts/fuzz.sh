#!/usr/bin/env bash
# fuzz.sh - fuzzes facet's readers of untrusted input with libFuzzer (Clang, ASan + UBSan).
# Usage: scripts/fuzz.sh --list            names the targets
#        scripts/fuzz.sh TARGET SECONDS    builds what is missing, then fuzzes TARGET for SECONDS from a seed corpus
#                                          of Debian's assimp-testmodels; exits non-zero on any finding, whose input
#                                          libFuzzer writes to build-fuzz/findings/TARGET/.
# A finding, once fixed, joins tests/fuzz/regressions/FORMAT/, which every test run reads through the same reader.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
targets=(obj ply stl gltf image batch)
if [ "${1:-}" = --list ]; then
  printf '%s\n' "${targets[@]}"
  exit 0
fi
if [ $# -ne 2 ] || [[ ! " ${targets[*]} " =~ " $1 " ]] || [[ ! $2 =~ ^[0-9]+$ ]]; then
  echo "usage: scripts/fuzz.sh --list | scripts/fuzz.sh TARGET SECONDS (targets: ${targets[*]})" >&2
  exit 2
fi
target=$1 seconds=$2
scripts/deps.sh
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
[ -f build-fuzz/build.ninja ] || cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$(nproc)" --target "fuzz_$target" >/dev/null

# The seed corpus: real files of the target's formats, and the regression inputs.
models=/usr/share/assimp/models
corpus=build-fuzz/corpus/$target
findings=build-fuzz/findings/$target
mkdir -p "$corpus" "$findings"
seed() {  # seed FIND-ARGS...: copies matching files under 1000 KiB into the corpus, named by their content
  find "$models" -type f -size -1000k "$@" -print0 | while IFS= read -r -d '' f; do
    cp "$f" "$corpus/$(md5sum <"$f" | cut -c1-16)"
  done
}
case $target in
  obj) seed -iname '*.obj' ;;
  ply) seed -iname '*.ply' ;;
  stl) seed -iname '*.stl' ;;
  gltf) seed \( -iname '*.gltf' -o -iname '*.glb' \) ;;
  image) seed \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.tga' -o -iname '*.bmp' \) ;;
  batch)
    printf '{"model": "a.obj", "output": "x/{stem}.png", "resolution": [64, 48], "no-background": true}\n' \
      >"$corpus/json"
    printf 'a.obj\n# comment\nb.glb\n' >"$corpus/list" ;;
esac
# Regression inputs; NAME.patch is a file of assimp-testmodels with some bytes changed (test_fuzz_regressions.cpp).
for input in tests/fuzz/regressions/"$target"/*; do
  [ -f "$input" ] || continue
  if [[ $input == *.patch ]]; then
    python3 - "$input" "$corpus/$(basename "$input" .patch)" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1]))
data = bytearray(open(spec['base'], 'rb').read())
for offset, run in spec['patches']:
    data[offset:offset + len(run) // 2] = bytes.fromhex(run)
open(sys.argv[2], 'wb').write(data)
PY
  else
    cp "$input" "$corpus/"
  fi
done

echo "fuzz.sh: fuzzing $target for $seconds s from $(find "$corpus" -type f | wc -l) inputs" >&2
# -rss_limit_mb and -malloc_limit_mb: an input that makes a reader claim more than 2 GB is a finding too.
exec "build-fuzz/tests/fuzz/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
  -malloc_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1
