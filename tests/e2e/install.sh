#!/usr/bin/env bash
# install.sh - installs the built tree into a scratch prefix, then builds and runs a consumer against it twice:
# with find_package(facet) and with pkg-config. Usage: install.sh BUILD_DIR SOURCE_DIR SCRATCH.
set -euo pipefail
build=$1
source=$2
scratch=$3
rm -rf "$scratch"
mkdir -p "$scratch"
prefix=$scratch/prefix

cmake --install "$build" --prefix "$prefix" >"$scratch/install.log"
for f in bin/facet lib/libfacet.a include/facet/renderer.hpp lib/cmake/facet/facetConfig.cmake \
         lib/cmake/facet/facetConfigVersion.cmake lib/pkgconfig/facet.pc; do
  [ -f "$prefix/$f" ] || { echo "FAIL: $f was not installed"; exit 1; }
done
"$prefix/bin/facet" --version >/dev/null

check_png() {
  python3 - "$1" <<'PY'
import struct, sys
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
width, height = struct.unpack('>II', data[16:24])
assert (width, height) == (320, 240), (width, height)
PY
}

# find_package(facet CONFIG), in a build folder of its own (the consumer's sources are outside the build tree).
cmake -S "$source/examples/consumer" -B "$scratch/cmake-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >"$scratch/configure.log"
cmake --build "$scratch/cmake-build" >"$scratch/build.log"
"$scratch/cmake-build/consumer" "$scratch/cmake.png"
check_png "$scratch/cmake.png"

# pkg-config: the flags alone build it.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
# shellcheck disable=SC2046  # pkg-config's output is meant to split into flags
${CXX:-c++} -std=c++20 -O1 -o "$scratch/pc-consumer" "$source/examples/consumer/main.cpp" \
  $(pkg-config --cflags --libs facet)
"$scratch/pc-consumer" "$scratch/pc.png"
check_png "$scratch/pc.png"
cmp -s "$scratch/cmake.png" "$scratch/pc.png" || { echo "FAIL: the two consumers' images differ"; exit 1; }

# A consumer of the readers and writers (examples/render_job): render() pulls in the glTF reader with Draco, the Assimp reader (Assimp is
# opened at run time) and the OpenEXR writer. Built both ways, it renders a Draco glTF and a COLLADA file.
cmake -S "$source/examples/render_job" -B "$scratch/render-job/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" >"$scratch/render-job.log"
cmake --build "$scratch/render-job/build" >>"$scratch/render-job.log"
# shellcheck disable=SC2046  # pkg-config's output is meant to split into flags
${CXX:-c++} -std=c++20 -O1 -o "$scratch/render-job/pc-render-job" "$source/examples/render_job/main.cpp" \
  $(pkg-config --cflags --libs facet)
for program in "$scratch/render-job/build/render_job" "$scratch/render-job/pc-render-job"; do
  for model in glTF2/draco/2CylinderEngine.gltf Collada/duck.dae; do
    rm -f "$scratch/job.png" "$scratch/job.exr"
    "$program" "/usr/share/assimp/models/$model" "$scratch/job.png" "$scratch/job.exr" ||
      { echo "FAIL: $program did not render $model"; exit 1; }
    [ "$(head -c 4 "$scratch/job.exr" | od -An -tx1 | tr -d ' ')" = 762f3101 ] ||
      { echo "FAIL: $program wrote no EXR for $model"; exit 1; }
  done
done

# The Python package, where the build made one: the installed copy imports and renders, with no build tree in sight.
if [ -d "$build/python/facet" ]; then
  (cd "$scratch" && PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 - "$prefix" <<'PY'
import sys
import facet
assert facet.__file__.startswith(sys.argv[1]), facet.__file__
out = facet.render("/usr/share/assimp/models/OBJ/box.obj", width=32, height=24, buffers=["mask"])
assert out["mask"].shape == (24, 32) and out["mask"].any()
PY
  ) || { echo "FAIL: the installed Python package does not import and render"; exit 1; }
fi
echo "1 passed, 0 failed"
