#!/usr/bin/env bash
# expect_error.sh - compiles one file for syntax only: it must fail with the message on its "// expect-error:" line.
# Usage: expect_error.sh COMPILER SOURCE INCLUDE_DIRS (colon-separated). A file without that line must compile: the
# control, which shows the include paths and flags are sound, so no test passes merely because nothing compiles.
set -u
compiler=$1 source=$2
flags=(-std=c++20 -fsyntax-only -Wall -Wextra -Werror -Wno-psabi)
IFS=: read -ra dirs <<< "$3"
for dir in "${dirs[@]}"; do
  # The compiler's own system folder stays implicit: naming it with -I would reorder the standard headers.
  [[ -n $dir && $dir != /usr/include && $dir != /usr/local/include ]] && flags+=("-I$dir")
done
expected=$(sed -n 's|^// expect-error: ||p' "$source")
output=$("$compiler" "${flags[@]}" "$source" 2>&1)
status=$?
if [[ -z $expected ]]; then
  [[ $status -eq 0 ]] && exit 0
  printf 'FAIL: %s should compile, but:\n%s\n' "$source" "$output"
  exit 1
fi
if [[ $status -eq 0 ]]; then
  printf 'FAIL: %s compiled; it should fail with: %s\n' "$source" "$expected"
  exit 1
fi
if grep -qF -- "$expected" <<< "$output"; then
  printf 'ok: %s fails with: %s\n' "$source" "$expected"
  exit 0
fi
printf 'FAIL: %s failed without the message: %s\n%s\n' "$source" "$expected" "$output"
exit 1
