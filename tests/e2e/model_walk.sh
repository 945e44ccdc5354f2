#!/usr/bin/env bash
# model_walk.sh - the loaders' regression suite: every model of Debian's assimp-testmodels in glTF2/, PLY/, STL/,
# OBJ/ and invalid/, and one file of six other formats, through `facet render` with no flags but the output.
# Each renders with the model in view, or fails with status 1, one "facet: error: FILE: problem" line and no file.
# Usage: model_walk.sh FACET SCRATCH. Prints one line per file that breaks the rule and a closing summary.
set -uo pipefail
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.bash"
facet=$1
scratch=$2
models=/usr/share/assimp/models
rm -rf "$scratch"
mkdir -p "$scratch"

files=()
while IFS= read -r -d '' f; do files+=("$f"); done < <(
  find "$models/glTF2" -type f \( -name '*.gltf' -o -name '*.glb' \) -print0
  find "$models/PLY" "$models/STL" "$models/invalid" -type f -print0
  find "$models/OBJ" -type f -name '*.obj' -print0)
files+=("$models/FBX/box.fbx" "$models/Collada/duck.dae" "$models/3DS/fels.3ds" "$models/OFF/Cube.off"
        "$models/X3D/ComputerKeyboard.x3d" "$models/3MF/box.3mf")

rendered=() refused=0
for f in "${files[@]}"; do
  out=$scratch/$((${#rendered[@]} + refused)).png
  timeout 60 "$facet" render "$f" --output "$out" --resolution 96,72 --no-background 2>"$scratch/stderr.txt"
  status=$?
  if [ $status -eq 0 ]; then
    rendered+=("$out|$f")
  elif [ $status -eq 1 ]; then
    refused=$((refused + 1))
    lines=$(wc -l <"$scratch/stderr.txt")
    errors=$(grep -cF "facet: error: $f" "$scratch/stderr.txt")
    # Warnings may come first; the error is one line, the last, and names the file.
    if [ "$errors" -ne 1 ] || ! tail -n 1 "$scratch/stderr.txt" | grep -q "^facet: error: "; then
      bad "$f" "refused without one error line naming it ($lines lines): $(tail -n 2 "$scratch/stderr.txt")"
    elif [ -e "$out" ]; then
      bad "$f" "refused but wrote $out"
    fi
  else
    bad "$f" "exit status $status: $(tail -n 2 "$scratch/stderr.txt")"
  fi
done

# The rendered images, checked in one python run: some model pixel (alpha > 0) and a transparent corner.
cat "$e2e_lib/png.py" - >"$scratch/check.py" <<'EOF'
for entry in sys.argv[1:]:
    path, model = entry.split('|', 1)
    w, h, ch, rows = read_png(path)
    covered = sum(rows[y][x * 4 + 3] > 0 for y in range(h) for x in range(w)) if ch == 4 else 0
    if ch != 4 or rows[0][3] != 0 or covered == 0:
        print(f'{model}: {ch} channels, corner alpha {rows[0][ch - 1]}, {covered} model pixels')
EOF
problems=$(python3 "$scratch/check.py" "${rendered[@]}")
if [ -n "$problems" ]; then
  while IFS= read -r line; do bad "$line" "rendered without the model in view"; done <<<"$problems"
fi
ok "${#files[@]} files: ${#rendered[@]} rendered with the model in view, $refused refused cleanly"
[ ${#rendered[@]} -gt 60 ] || bad "fewer files rendered than expected" "${#rendered[@]}"
finish
