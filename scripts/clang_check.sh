#!/usr/bin/env bash
# clang_check.sh - compiles the library, the CLI, the examples and the benchmarks with Clang, front end only,
# warnings as errors. Usage: clang_check.sh BUILD_DIR (a configured build; its compile_commands.json is reused).
# The front end is where the compilers differ (builtins, attributes, warnings), at a fraction of a full Clang
# build's time. These files include every public header and instantiate the pipeline for the stock shaders; the
# tests, which would double the time, add GoogleTest and no other facet code.
set -euo pipefail
build=${1:?usage: clang_check.sh BUILD_DIR}
clang=$(command -v clang++ || true)
[ -n "$clang" ] || { echo "clang_check.sh: clang++ not found (scripts/deps.sh installs it)" >&2; exit 1; }
# ccache caches front-end-only runs (with their warnings) like compiles, so unchanged files cost a lookup.
launcher=$(command -v ccache || true)
commands=$build/compile_commands.json
[ -f "$commands" ] || { echo "clang_check.sh: $commands not found (configure the build first)" >&2; exit 1; }

# One line per file: the GCC command with Clang in place of the compiler and no output file.
python3 - "$commands" "$clang" "$launcher" > "$build/clang_check.commands" <<'PY'
import json, shlex, sys
entries, clang, launcher = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3]
for e in entries:
    if "/tests/" in e["file"] and not e["file"].endswith("support/test_shaders.cpp"):
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
