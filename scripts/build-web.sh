#!/usr/bin/env bash
# build-web.sh - installs what is missing and builds the browser page into build-web/ (index.html, facet.js,
# facet.wasm, a sample model), which any static file server can serve: python3 -m http.server -d build-web.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
scripts/deps.sh
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
# Debian's Emscripten runs its JavaScript tools with the system Node.js, whose modules it finds here.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
# Emscripten builds its system libraries into a cache the first time; Debian's default cache is under /usr, which
# only root may write, so an ordinary user's build keeps its own.
if [ ! -w /usr/share/emscripten/cache ]; then
  export EM_CACHE=${EM_CACHE:-$HOME/.cache/facet-emscripten}
fi
emcmake cmake -S web -B build-web -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-web -j "$(nproc)"
echo "build-web.sh: the page is in build-web/ (serve it: python3 -m http.server -d build-web 8000)"
