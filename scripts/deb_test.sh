#!/usr/bin/env bash
# deb_test.sh - builds the Debian packages with cpack and installs them with apt into a fresh bookworm root.
# Usage: deb_test.sh BUILD_DIR SOURCE_DIR SCRATCH   (ctest's package.deb runs it)
# In the root (mmdebstrap, the apt variant) the facet program renders a glTF file, the Python module imports and
# renders, and a small program built against facet-dev, with find_package(facet) and with pkg-config, renders.
# It needs root, for the chroot, and Debian's mirror; without root it exits 77, which ctest reports as skipped.
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
scratch=$3
models=/usr/share/assimp/models
if [ "$(id -u)" -ne 0 ]; then
  echo "skipped: making a Debian root and installing packages into it needs root"
  exit 77
fi
# shellcheck source=SCRIPTDIR/../tests/e2e/lib/common.bash
source "$source/tests/e2e/lib/common.bash"

command -v mmdebstrap >/dev/null || "$source/scripts/deps.sh"
rm -rf "$scratch"
mkdir -p "$scratch/debs" "$scratch/in/model" "$scratch/out"
scratch=$(cd "$scratch" && pwd)

# The packages, as `cpack -G DEB` in the build folder makes them.
if ! cpack --config "$build/CPackConfig.cmake" -G DEB -B "$scratch/debs" >"$scratch/cpack.log" 2>&1; then
  tail -20 "$scratch/cpack.log"
  bad "cpack makes the packages" "log: $scratch/cpack.log"
  finish
fi
runtime=$(find "$scratch/debs" -maxdepth 1 -name 'facet_*.deb')
dev=$(find "$scratch/debs" -maxdepth 1 -name 'facet-dev_*.deb')
[ -f "$runtime" ] && [ -f "$dev" ] || { bad "cpack makes facet and facet-dev" "$(ls "$scratch/debs")"; finish; }
ok "cpack makes $(basename "$runtime") and $(basename "$dev")"

# Their metadata and contents, before anything is installed.
for deb in "$runtime" "$dev"; do
  echo "$(dpkg-deb -f "$deb" Package) Depends: $(dpkg-deb -f "$deb" Depends)"
  echo "$(dpkg-deb -f "$deb" Package) Recommends: $(dpkg-deb -f "$deb" Recommends)"
  { dpkg-deb -f "$deb"; dpkg -c "$deb"; echo; } >>"$scratch/contents.txt"
done
fields() { dpkg-deb -f "$1" Package Version Section Maintainer | tr '\n' ' '; }
version=$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$build/CMakeCache.txt")
for deb in "$runtime" "$dev"; do
  name=$(dpkg-deb -f "$deb" Package)
  want="Package: $name Version: $version Section: graphics Maintainer: facet developers "
  [ "$(fields "$deb")" = "$want" ] && [ -z "$(dpkg-deb -f "$deb" Homepage)" ] && ok "$name's control fields" ||
    bad "$name's control fields" "$(fields "$deb")"
done
# Listed once into a file: grep -q would stop reading early and, under pipefail, fail dpkg's pipe.
for deb in "$runtime" "$dev"; do dpkg -c "$deb" | awk '{print $6}' >"$deb.files"; done
has() { grep -qx -- "$2" "$1.files"; }
missing=""
has "$runtime" ./usr/bin/facet || missing+=" /usr/bin/facet"
for f in ./usr/share/thumbnailers/facet.thumbnailer ./usr/share/mime/packages/facet.xml; do
  has "$runtime" "$f" || missing+=" $f"
done
# The Python module, where the build made one (FACET_BUILD_PYTHON).
python=0
[ -d "$build/python/facet" ] && python=1
if [ $python = 1 ]; then
  has "$runtime" ./usr/lib/python3/dist-packages/facet/__init__.py || missing+=" facet/__init__.py"
  grep -q '/dist-packages/facet/_facet\.cpython-.*\.so$' "$runtime.files" || missing+=" facet/_facet*.so"
fi
for f in ./usr/include/facet/renderer.hpp ./usr/include/facet/version.hpp ./usr/lib/libfacet.a \
         ./usr/lib/cmake/facet/facetConfig.cmake ./usr/lib/cmake/facet/facetConfigVersion.cmake \
         ./usr/lib/cmake/facet/facetTargets.cmake ./usr/lib/pkgconfig/facet.pc; do
  has "$dev" "$f" || missing+=" $f"
done
[ -z "$missing" ] && ok "each package holds its files" || bad "each package holds its files" "missing$missing"
shared=$(comm -12 <(grep -v '/$' "$runtime.files" | sort) <(grep -v '/$' "$dev.files" | sort))
[ -z "$shared" ] && ok "no file is in both packages" || bad "no file is in both packages" "$shared"
# dpkg-shlibdeps filled in the libraries the program links; the module needs Python and NumPy.
depends=" $(dpkg-deb -f "$runtime" Depends),"
absent=""
wanted=(libc6 libstdc++6 libtinygltf2d)
[ $python = 1 ] && wanted+=(python3 python3-numpy)
for p in "${wanted[@]}"; do
  [[ $depends == *" $p "* || $depends == *" $p,"* ]] || absent+=" $p"
done
[ -z "$absent" ] && ok "facet's Depends name the linked libraries (dpkg-shlibdeps) and Python" ||
  bad "facet's Depends name the linked libraries and Python" "no$absent in$depends"

# What the root gets: the packages, two models, a small program (examples/render_job) and the script that uses
# them there.
cp "$runtime" "$dev" "$scratch/in/"
cp "$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" "$models/Collada/duck.dae" "$models/Collada/duckCM.tga" \
   "$scratch/in/model/"
cp "$source/examples/render_job/main.cpp" "$source/examples/render_job/CMakeLists.txt" "$scratch/in/"
cat >"$scratch/in/inside.sh" <<'INSIDE'
# inside.sh - runs in the fresh root as root: installs the packages with apt and uses them. Each check prints an
# "ok" or "FAIL" line to out/results.txt, which deb_test.sh counts; it goes on past a failure so that mmdebstrap's
# next hook still copies out/ (with the logs) from the root.
cd /tmp/facet-test || exit 1
export DEBIAN_FRONTEND=noninteractive
apt=(apt-get -y -q --no-install-recommends install)
ok() { echo "ok   $1" | tee -a out/results.txt; }
bad() { echo "FAIL $1${2:+: $2}" | tee -a out/results.txt; }
png_size() {  # prints WIDTHxHEIGHT of a PNG file, or nothing; coreutils alone, as python3 may not be installed
  [ "$(head -c 8 "$1" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] &&
    od -An -tu4 --endian=big -j16 -N8 "$1" | awk '{print $1 "x" $2}'
}

# The program's package alone, with only its Depends: they must be enough to render and to import the module.
if "${apt[@]}" ./facet_*.deb >out/apt-facet.log 2>&1; then ok "apt installs facet"; else
  tail -5 out/apt-facet.log; bad "apt installs facet" "out/apt-facet.log"; exit 0; fi
facet --version >out/version.txt 2>&1 && ok "facet --version: $(head -1 out/version.txt)" ||
  bad "facet --version" "$(cat out/version.txt)"
facet render model/BoxTextured.glb --output out/box.png --resolution 64,48 >out/render.log 2>&1
[ "$(png_size out/box.png)" = 64x48 ] && ok "facet renders a glTF file to a PNG" ||
  bad "facet renders a glTF file" "$(tail -3 out/render.log)"
facet thumbnail -s 64 file:///tmp/facet-test/model/BoxTextured.glb out/thumb.png >out/thumb.log 2>&1
[ "$(png_size out/thumb.png)" = 64x64 ] && ok "facet thumbnail draws a glTF file's thumbnail" ||
  bad "facet thumbnail draws a glTF file's thumbnail" "$(tail -3 out/thumb.log)"
if [ -d /usr/lib/python3/dist-packages/facet ]; then
  (cd / && python3 - <<'PY') >out/python.log 2>&1 && ok "python3 imports facet and renders" ||
import facet
assert facet.__file__.startswith("/usr/lib/python3/dist-packages/facet/"), facet.__file__
out = facet.render("/tmp/facet-test/model/BoxTextured.glb", width=32, height=24, buffers=["mask"])
assert out["mask"].shape == (24, 32) and out["mask"].any()
PY
    bad "python3 imports facet and renders" "$(tail -3 out/python.log)"
fi

# The recommended Assimp: without it a COLLADA file is refused, naming the package; with it, the file renders.
recommends=$(dpkg-query -W -f '${Recommends}' facet)
if facet render model/duck.dae --output out/duck.png --resolution 64,48 >out/duck.log 2>&1; then
  bad "without Assimp, facet names its package" "the COLLADA file rendered"
elif grep -q "$recommends" out/duck.log; then ok "without Assimp, facet asks for $recommends"; else
  bad "without Assimp, facet asks for $recommends" "$(cat out/duck.log)"; fi
"${apt[@]}" "$recommends" >out/apt-assimp.log 2>&1 || bad "apt installs $recommends" "out/apt-assimp.log"
facet render model/duck.dae --output out/duck.png --resolution 64,48 >out/duck.log 2>&1
[ "$(png_size out/duck.png)" = 64x48 ] && ok "with $recommends, facet renders a COLLADA file" ||
  bad "with $recommends, facet renders a COLLADA file" "$(tail -3 out/duck.log)"
suggests=$(dpkg-query -W -f '${Suggests}' facet | tr -d ',')
# shellcheck disable=SC2086  # one package name a word
apt-cache show $suggests >/dev/null 2>&1 && ok "the suggested packages exist: $suggests" ||
  bad "the suggested packages exist" "$suggests"

# The -dev package and a compiler: a small program finds facet with find_package (no prefix given: the package's
# place is one CMake searches) and with pkg-config, and both builds render the same picture.
if "${apt[@]}" ./facet-dev_*.deb g++ cmake make >out/apt-dev.log 2>&1; then ok "apt installs facet-dev"; else
  tail -5 out/apt-dev.log; bad "apt installs facet-dev" "out/apt-dev.log"; exit 0; fi
if cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >out/cmake.log 2>&1 && cmake --build build >>out/cmake.log 2>&1 &&
   build/render_job model/BoxTextured.glb out/job-cmake.png >>out/cmake.log 2>&1 &&
   [ "$(png_size out/job-cmake.png)" = 64x48 ]; then
  ok "a program built with find_package(facet) renders"
else bad "a program built with find_package(facet) renders" "$(tail -5 out/cmake.log)"; fi
# shellcheck disable=SC2046  # pkg-config's output is meant to split into flags
if g++ -std=c++20 -O1 -o pc_render_job main.cpp $(pkg-config --cflags --libs facet) >out/pc.log 2>&1 &&
   ./pc_render_job model/BoxTextured.glb out/job-pc.png >>out/pc.log 2>&1 && [ "$(png_size out/job-pc.png)" = 64x48 ]
then ok "a program built with pkg-config's flags for facet renders"
else bad "a program built with pkg-config's flags for facet renders" "$(tail -5 out/pc.log)"; fi
cmp -s out/job-cmake.png out/job-pc.png && ok "both builds render the same picture" ||
  bad "both builds render the same picture"
dpkg --audit >out/audit.log 2>&1 && [ ! -s out/audit.log ] && ok "dpkg --audit finds nothing amiss" ||
  bad "dpkg --audit finds nothing amiss" "$(cat out/audit.log)"
INSIDE
chmod -R a+rX "$scratch/in"

# The root: bookworm's apt variant (essential packages and apt), from the mirror mmdebstrap picks by default. The
# checks run as its customize hooks, with /proc and /dev mounted; the null format drops the root afterwards.
start=$SECONDS
# In memory where there is a tmpfs: on this disk (ext4 with discard) dpkg's syncs and deleting the 800 MB root took
# most of two minutes.
[ -d /dev/shm ] && [ -w /dev/shm ] && export TMPDIR=/dev/shm
mmdebstrap --variant=apt \
  --customize-hook='mkdir -p "$1"/tmp/facet-test/out' \
  --customize-hook="sync-in '$scratch/in' /tmp/facet-test" \
  --customize-hook='chroot "$1" bash /tmp/facet-test/inside.sh' \
  --customize-hook="sync-out /tmp/facet-test/out '$scratch/out'" \
  bookworm /dev/null 2>&1 | perl -MPOSIX -ne '$|=1; print strftime("%T ", localtime), $_' >"$scratch/mmdebstrap.log" ||
  { tail -20 "$scratch/mmdebstrap.log"; bad "mmdebstrap"; }
echo "the root took $((SECONDS - start)) s (log: $scratch/mmdebstrap.log)"

# The checks made inside, counted here.
[ -s "$scratch/out/results.txt" ] || bad "the checks in the root ran" "no results"
while read -r status text; do
  if [ "$status" = ok ]; then ok "root: $text"; else bad "root: ${text%%: *}" "${text#*: }"; fi
done <"$scratch/out/results.txt" 2>/dev/null || true

# The installed program draws what the build tree's draws: the same pixels (the PNG files' bytes may differ with
# the zlib they are compressed by).
if [ -f "$scratch/out/box.png" ]; then
  "$build/tools/facet" render "$models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb" --output "$scratch/box.png" \
    --resolution 64,48 >/dev/null
  if python3 - "$e2e_lib" "$scratch/out/box.png" "$scratch/box.png" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from png import read_png
assert read_png(sys.argv[2]) == read_png(sys.argv[3])
PY
  then ok "the packaged program draws the build's pixels"; else bad "the packaged program draws the build's pixels"; fi
fi
finish
