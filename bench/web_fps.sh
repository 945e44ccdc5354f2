#!/usr/bin/env bash
# web_fps.sh - the browser page's frame rate in headless Chromium at 800x600: the torus demo and a model of about
# 100k triangles (Debian's assimp-testmodels). Usage: bench/web_fps.sh [ROUNDS] [SECONDS]   (default 3 rounds of 5 s).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
rounds=${1:-3}
seconds=${2:-5}
bash scripts/build-web.sh >/dev/null
(cd build-web && npm ci --no-audit --no-fund --ignore-scripts >/dev/null)
# The page opens models by address from its own origin, so the benchmark's model is put beside it.
mkdir -p build-web/bench
model=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb  # 121,496 triangles
cp "$model" build-web/bench/
node bench/web_fps.mjs build-web "$seconds" "$rounds" "?size=800x600&show=demo:torus" \
  "?size=800x600&show=model:bench/$(basename "$model")"
