#!/usr/bin/env bash
# web_page.sh - builds the browser page (scripts/build-web.sh), drives it in headless Chromium (web_page.mjs) and
# checks that it draws what the CLI draws. Usage: web_page.sh FACET SOURCE_DIR OUT_DIR
set -euo pipefail
facet=$1
src=$(cd "$2" && pwd)
out=$3
mkdir -p "$out"
if ! bash "$src/scripts/build-web.sh" >"$out/build.log" 2>&1; then
  tail -30 "$out/build.log"
  echo "FAIL the page builds (log: $out/build.log)"
  exit 1
fi
# playwright-core, at the version web/package-lock.json pins, next to the page it drives.
if ! (cd "$src/build-web" && npm ci --no-audit --no-fund --ignore-scripts >"$out/npm.log" 2>&1); then
  tail -20 "$out/npm.log"
  echo "FAIL npm ci (log: $out/npm.log)"
  exit 1
fi
# For its python3: the system one.
# shellcheck source=SCRIPTDIR/lib/common.bash
source "$src/tests/e2e/lib/common.bash"
status=0
node "$src/tests/e2e/web_page.mjs" "$src/build-web" "$out" || status=1

# The same model, size and view through the native CLI: the WebAssembly build (Clang, 128-bit SIMD, musl's maths)
# must draw the same picture as the host build (GCC, AVX-512 or AVX2 clones, glibc's).
"$facet" render /usr/share/assimp/models/OBJ/WusonOBJ.obj --output "$out/cli_wuson.png" --resolution 640,480 \
  --samples 1
python3 - "$src/tests/e2e/lib" "$out/page_wuson.png" "$out/cli_wuson.png" <<'PY' || status=1
import sys
sys.path.insert(0, sys.argv[1])
from png import read_png
(w1, h1, c1, page), (w2, h2, c2, cli) = read_png(sys.argv[2]), read_png(sys.argv[3])
if (w1, h1) != (w2, h2):
    sys.exit(f"FAIL the page draws what the CLI draws: {w1}x{h1} against {w2}x{h2}")
differ, worst = 0, 0
for y in range(h1):
    for x in range(w1):
        a, b = page[y][x * c1:x * c1 + 3], cli[y][x * c2:x * c2 + 3]
        if a != b:
            differ += 1
            worst = max(worst, max(abs(p - q) for p, q in zip(a, b)))
print(f"{'ok  ' if differ == 0 else 'FAIL'} the page draws what the CLI draws ({differ} pixels differ, by up to {worst})")
sys.exit(differ != 0)
PY
exit $status
