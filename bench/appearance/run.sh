#!/usr/bin/env bash
# run.sh - renders glTF models in facet and in three.js through the same camera and environment, and tabulates how far
# the pictures differ. Usage: bash bench/appearance/run.sh FACET OUT_DIR [MODEL...]
# (default models: the synthetic ones of make_models.py and some of Debian's assimp-testmodels).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
facet=$(realpath "$1")
out=$(mkdir -p "$2" && cd "$2" && pwd)
shift 2

resolution=512,512
background=0.42,0.45,0.5   # facet's own default, passed to both sides so neither relies on it
tone_mapping=neutral exposure=1
# The same environment, tone mapping and exposure on both sides.
pbr_flags=(--hdri "$out/studio.hdr" --tone-mapping "$tone_mapping" --exposure "$exposure")
three_flags=(--hdri "$out/studio.hdr" --tone-mapping "$tone_mapping" --exposure "$exposure" --background "$background")

# The system python3 has numpy; a version manager's shim earlier on PATH may not.
python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3

if [ ! -d "$here/node_modules" ]; then
  (cd "$here" && npm ci --no-audit --no-fund --ignore-scripts >/dev/null)
fi
"$python" "$here/studio_hdr.py" "$out/studio.hdr"
"$python" "$here/make_models.py" "$out/models"

if [ $# -eq 0 ]; then
  assimp=/usr/share/assimp/models/glTF2
  set -- "$out"/models/{sweep,default_material,emissive,blend,factors,textured,layers,glass,tangents}.gltf \
    $assimp/2CylinderEngine-glTF-Binary/2CylinderEngine.glb \
    $assimp/BoxTextured-glTF-Binary/BoxTextured.glb \
    $assimp/ClearCoat-glTF/ClearCoatTest.gltf \
    $assimp/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf \
    $assimp/textureTransform/TextureTransformTest.gltf \
    $assimp/BoxTexcoords-glTF/boxTexcoords.gltf \
    $assimp/cameras/Cameras.gltf \
    $assimp/simple_skin/simple_skin.gltf
fi

# facet first: its camera JSON is what three.js renders through.
declare -A note=()
names=()
jobs=()  # model, camera, output for each model facet drew
for model in "$@"; do
  name=$(basename "${model%.*}")
  if [[ " ${names[*]} " == *" $name "* ]]; then name+="_${#names[@]}"; fi  # two models of one name
  flags=(--output "$out/facet_$name.png" --output-camera "$out/$name.camera.json" --resolution "$resolution"
         --background-color "$background")
  rm -f "$out/facet_$name.png"
  if ! "$facet" render "$model" "${flags[@]}" "${pbr_flags[@]}" >"$out/facet_$name.log" 2>&1; then
    echo "facet failed on $model (log: $out/facet_$name.log)"
    note[$name]=" (facet failed)"
    names+=("$name")
    continue
  fi
  names+=("$name")
  jobs+=("$model" "$out/$name.camera.json" "$out/three_$name.png")
done
"$python" -c 'import json, sys
a = sys.argv[1:]
print(json.dumps([dict(zip(("model", "camera", "output"), a[i:i + 3])) for i in range(0, len(a), 3)], indent=1))' \
  "${jobs[@]}" >"$out/jobs.json"

# All three.js renders in one browser session; a model it cannot draw leaves no image and its row says so.
rm -f "$out"/three_*.png
node "$here/three_render.mjs" --jobs "$out/jobs.json" "${three_flags[@]}" || echo "three.js failed on some models"

table="| model | mean abs diff | SSIM |"$'\n'"|---|---:|---:|"
for name in "${names[@]}"; do
  a="$out/facet_$name.png" b="$out/three_$name.png"
  if [ -f "$a" ] && [ -f "$b" ]; then
    read -r _ _ _ mad _ ssim < <("$python" "$here/compare.py" "$a" "$b" --diff "$out/diff_$name.png")
    table+=$'\n'"| $name${note[$name]:-} | $mad | $ssim |"
  else
    if [ -f "$a" ]; then note[$name]="${note[$name]:-} (three.js failed)"; fi
    table+=$'\n'"| $name${note[$name]:-} | - | - |"
  fi
done
echo "$table" | tee "$out/table.md"
