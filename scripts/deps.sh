#!/usr/bin/env bash
# deps.sh - installs the Debian packages facet needs to build, test and benchmark, skipping those already present.
# Usage: scripts/deps.sh [PACKAGE...]   (extra packages a script needs besides these, e.g. perf.sh's f3d)
set -euo pipefail

packages=(g++ cmake ninja-build pkg-config libglm-dev libstb-dev libtinyobjloader-dev libtinygltf-dev libassimp-dev libopenexr-dev libdraco-dev libmeshoptimizer-dev liblzf-dev libisal-dev zlib1g-dev libcli11-dev nlohmann-json3-dev
          libgtest-dev libgmock-dev libbenchmark-dev assimp-testmodels python3 time ccache clang parallel dpkg-dev mmdebstrap
          python3-dev pybind11-dev python3-numpy python3-pytest python3-setuptools python3-pip python3-pil
          libsdl2-dev xvfb xauth libgif-dev libspng-dev libturbojpeg0-dev libavcodec-dev libavformat-dev libswscale-dev ffmpeg
          shared-mime-info bubblewrap slurm-wlm munge python3-distributed python3-yaml
          libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri qemu-user emscripten chromium
          googletest g++-aarch64-linux-gnu "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
# npm (for the browser test's playwright-core) comes with Debian's nodejs as its own package, or inside another
# Node.js build (NodeSource's conflicts with Debian's npm): ask for Debian's only when no npm is there.
command -v npm >/dev/null || missing+=(nodejs npm)
[ ${#missing[@]} -eq 0 ] && exit 0

echo "deps.sh: installing ${missing[*]}" >&2
apt=(env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=300 -y)
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "deps.sh: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  apt=(sudo "${apt[@]}")
fi
# A fresh machine has no package lists yet, so update first when the plain install fails.
"${apt[@]}" install --no-install-recommends "${missing[@]}" ||
  { "${apt[@]}" update && "${apt[@]}" install --no-install-recommends "${missing[@]}"; }
