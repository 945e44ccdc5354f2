#!/usr/bin/env bash
# golden_images.sh - renders the golden scenes with the CLI and compares them with tests/golden/images.
# Usage: golden_images.sh FACET SCRATCH [EXAMPLE...]. Each EXAMPLE is a program of examples/ that writes the PNG named
# by its one argument; its golden is example_<program name>.png. FACET_UPDATE_GOLDENS=1 rewrites the goldens instead (commit them apart).
# Exact: every pixel of every golden must match. The pipeline rounds alike at every thread count, on every CPU
# level and on the lane and scalar paths (docs/ARCHITECTURE.md), so the release build (AVX-512 or AVX2 clones) and
# the sanitizer build (the baseline) draw the same bits with the pinned toolchain, GCC 12 on Debian 12. Another
# compiler or C library may round a function such as powf differently and move a pixel by a level; regenerate the
# goldens for it. A failure leaves NAME.actual.png and NAME.diff.png (red = differing pixel) in SCRATCH.
set -uo pipefail
facet=$1
scratch=$2
examples=("${@:3}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
models=/usr/share/assimp/models/OBJ
mkdir -p "$scratch"
# Most goldens are single-sampled (--samples 1: the pipeline's own edges); the antialiased_ ones take the CLI's
# default of 4 samples, lines and edge overlays included.
size=(--resolution 240,180 --samples 1)
aa_size=(--resolution 240,180)

cases=(
  "demo_cube|demo cube ${size[*]}"
  "demo_torus|demo torus ${size[*]}"
  "demo_two_cubes|demo two-cubes ${size[*]}"
  "demo_pentagon|demo pentagon ${size[*]}"
  "textured_obj|render $models/spider.obj ${size[*]}"
  "wireframe|render $models/WusonOBJ.obj --wireframe ${size[*]}"
  "edges|render $models/box.obj --edges ${size[*]}"
  "antialiased_wuson|render $models/WusonOBJ.obj ${aa_size[*]}"
  "antialiased_edges|render $models/box.obj --edges ${aa_size[*]}"
  "antialiased_demo_torus|demo torus ${aa_size[*]}"
)
# glTF's three forms of the textured box (the separate one's sampler mirrors its texture in u and clamps it in v,
# the others repeat it); the texture transform test shows its "correct" marks (its
# squares' textures moved, turned and scaled, clamped at the edges); then a vertex-coloured PLY and a binary STL.
gltf=/usr/share/assimp/models/glTF2
cases+=("gltf_box_textured_binary|render $gltf/BoxTextured-glTF-Binary/BoxTextured.glb ${size[*]}")
cases+=("gltf_box_textured_embedded|render $gltf/BoxTextured-glTF-Embedded/BoxTextured.gltf ${size[*]}")
cases+=("gltf_box_textured_separate|render $gltf/BoxTextured-glTF/BoxTextured.gltf ${size[*]}")
cases+=("gltf_texture_transform|render $gltf/textureTransform/TextureTransformTest.gltf --resolution 320,240 --samples 1")
cases+=("ply_vertex_colors|render /usr/share/assimp/models/PLY/float-color.ply ${size[*]}")
cases+=("stl_binary|render /usr/share/assimp/models/STL/Spider_binary.stl ${size[*]}")
for p in perspective orthographic frustum oblique isometric dimetric trimetric front top side; do
  cases+=("projection_$p|render $models/WusonOBJ.obj --projection $p ${size[*]}")
done
for program in "${examples[@]}"; do
  cases+=("example_$(basename "$program")|@$program")
done

passed=0 failed=0
for entry in "${cases[@]}"; do
  name=${entry%%|*}
  read -r -a args <<<"${entry#*|}"
  actual=$scratch/$name.actual.png
  rm -f "$actual" "$scratch/$name.diff.png"
  if [[ ${args[0]} == @* ]]; then
    command=("${args[0]#@}" "$actual")  # an example program
  else
    command=("$facet" "${args[@]}" --output "$actual")
  fi
  if ! "${command[@]}" 2>"$scratch/$name.log"; then
    echo "FAIL $name: ${command[*]} failed: $(head -n 3 "$scratch/$name.log")"
    failed=$((failed + 1))
    continue
  fi
  golden=$here/images/$name.png
  if [ "${FACET_UPDATE_GOLDENS:-0}" = 1 ]; then
    cp "$actual" "$golden"
    echo "updated $name"
    passed=$((passed + 1))
    continue
  fi
  if [ ! -f "$golden" ]; then
    echo "FAIL $name: no golden image $golden (render it with FACET_UPDATE_GOLDENS=1)"
    failed=$((failed + 1))
    continue
  fi
  if result=$(python3 "$here/imagecmp.py" "$golden" "$actual" "$scratch/$name.diff.png" 0 0); then
    echo "ok   $name: $result"
    passed=$((passed + 1))
  else
    echo "FAIL $name: $result (actual $actual, diff $scratch/$name.diff.png)"
    failed=$((failed + 1))
  fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
