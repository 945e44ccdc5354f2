#!/usr/bin/env bash
# pyrender_compare.sh - runs pyrender's own unit tests (all but EGL's) against a module that is exactly
# `from facet import *`, then draws the same scenes, and pyrender's examples/example.py, with pyrender (on Mesa's
# llvmpipe through EGL) and with facet and checks that they agree (python/tests/test_pyrender_pixels.py). trimesh
# is python/tests/support's stand-in.
# Usage: scripts/pyrender_compare.sh PYRENDER_CHECKOUT [BUILD_DIR]
#   PYRENDER_CHECKOUT: a checkout of github.com/mmatl/pyrender (Debian does not package pyrender); its examples'
#   models must be there. Installs the Debian packages pyrender needs, skipping those already present.
set -euo pipefail
source_dir=$(cd "${1:?usage: $0 PYRENDER_CHECKOUT [BUILD_DIR]}" && pwd)
build=${2:-build}
here=$(cd "$(dirname "$0")/.." && pwd)
[ -d "$source_dir/pyrender" ] || { echo "pyrender_compare.sh: $source_dir has no pyrender/ folder" >&2; exit 1; }
bash "$here/scripts/deps.sh" python3-opengl python3-pyglet python3-scipy python3-networkx python3-imageio \
  python3-freetype python3-pil
shim=$(mktemp -d)
trap 'rm -rf "$shim"' EXIT
mkdir "$shim/pyrender"
echo "from facet import *" >"$shim/pyrender/__init__.py"
echo "from facet.constants import *" >"$shim/pyrender/constants.py"
# Run from the checkout (its tests open files relative to it) without putting it on the path (-P, and pytest's
# append mode), so that its own pyrender package does not shadow the shim.
(cd "$source_dir" && PYTHONPATH="$shim:$here/$build/python:$here/python/tests/support" \
  /usr/bin/python3 -P -m pytest -q -p no:cacheprovider --import-mode=append tests/unit --ignore=tests/unit/test_egl.py)
FACET_PYRENDER_SOURCE="$source_dir" PYTHONPATH="$here/$build/python" \
  /usr/bin/python3 -m pytest -q -s -p no:cacheprovider "$here/python/tests/test_pyrender_pixels.py"
