#!/usr/bin/env bash
# clang_check.sh - compiles the CLI, the apps, the examples, the benchmarks and the Python module with Clang, front
# end only, warnings as errors. Usage: clang_check.sh BUILD_DIR (a configured build; its compile_commands.json is
# reused). The front end is where the compilers differ (builtins, attributes, warnings), at a fraction of a full
# Clang build's time. The library (src/) is left to the test command's Clang build (the clang preset), which
# compiles it with the same warnings as errors; the tests, which would double the time, add GoogleTest and no other
# facet code. FACET_CLANG_CHECK_LIBRARY=1 checks the library's files here too.
set -euo pipefail
build=${1:?usage: clang_check.sh BUILD_DIR}
clang=$(command -v clang++ || true)
[ -n "$clang" ] || { echo "clang_check.sh: clang++ not found (scripts/deps.sh installs it)" >&2; exit 1; }
# ccache caches front-end-only runs (with their warnings) like compiles, so unchanged files cost a lookup.
launcher=$(command -v ccache || true)
commands=$build/compile_commands.json
[ -f "$commands" ] || { echo "clang_check.sh: $commands not found (configure the build first)" >&2; exit 1; }

# One line per file: the GCC command with Clang in place of the compiler and no output file.
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
python3 - "$commands" "$clang" "$launcher" "${FACET_CLANG_CHECK_LIBRARY:-0}" "$source_dir" \
  > "$build/clang_check.commands" <<'PY'
import json, os, shlex, sys
entries, clang, launcher, library = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3], sys.argv[4] == "1"
root = os.path.realpath(sys.argv[5])
for e in entries:
    if "/tests/" in e["file"] and not e["file"].endswith("support/test_shaders.cpp"):
        continue
    if not library and os.path.realpath(e["file"]).startswith(os.path.join(root, "src") + os.sep):
        continue
    args = e.get("arguments") or shlex.split(e["command"])
    out, skip = ([launcher] if launcher else []) + [clang], False
    for a in args[1:]:
        if skip: skip = False; continue
        if a == "-o": skip = True; continue
        if a == "-c": continue
        out.append(a)
    out += ["-fsyntax-only", "-Wall", "-Wextra", "-Werror"]
    print("cd " + shlex.quote(e["directory"]) + " && " + " ".join(map(shlex.quote, out)))
PY
count=$(wc -l < "$build/clang_check.commands")
tr '\n' '\0' < "$build/clang_check.commands" | xargs -0 -P "$(nproc)" -n 1 bash -c
echo "clang_check.sh: $count files compile warning-free with $($clang --version | head -1)"
