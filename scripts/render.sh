#!/usr/bin/env bash
# render.sh - installs what is missing, builds facet and renders a real model (assimp-testmodels' WusonOBJ) to out/wuson.png.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target facet_cli
mkdir -p out
build/tools/facet render /usr/share/assimp/models/OBJ/WusonOBJ.obj --output out/wuson.png "$@"
echo "wrote out/wuson.png"
