# common.bash - what the e2e scripts share: pass/fail counting, the closing summary line and the path to lib/.
# Sourced, not run. It lives under lib/ with a .bash name because tests/CMakeLists.txt registers every e2e/*.sh as a
# test (a non-recursive glob).
# shellcheck shell=bash

# The folder holding this file and png.py.
# shellcheck disable=SC2034  # used by the scripts that source this file
e2e_lib=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

passed=0 failed=0

# The checks run on the system python3, the one the Python module is built for: a python3 found earlier on PATH
# (a version manager's shim) can take a third of a second to start, and the scripts start it a hundred times.
facet_python=python3
[ -x /usr/bin/python3 ] && facet_python=/usr/bin/python3
python3() { command "$facet_python" "$@"; }

# ok MESSAGE, bad NAME [REASON]: one result line each, counted for the summary.
ok() { echo "ok   $1"; passed=$((passed + 1)); }
bad() { echo "FAIL $1${2:+: $2}"; failed=$((failed + 1)); }

# finish: prints "N passed, M failed"; call it last, so the script's exit status says whether anything failed.
finish() {
  echo "$passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}
