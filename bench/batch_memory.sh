#!/usr/bin/env bash
# batch_memory.sh - a batch's peak memory against its job count: 1,000, 10,000 and 100,000 thumbnails of the
# batch benchmark's six real models (32x32, so that 100,000 render in a couple of minutes on two cores), each job
# at its own angle and writing its own file. Usage: bench/batch_memory.sh FACET [LARGEST]. Prints the peak resident
# memory of each batch, its time, and the memory each job added beyond the smallest batch.
set -euo pipefail
facet=$(realpath "$1")
largest=${2:-100000}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

printf '%8s %12s %10s %14s\n' jobs "peak (KiB)" "time (s)" "KiB per job"
base=
for n in 1000 10000 "$largest"; do
  python3 "$here/thumbnail_jobs.py" "$n" 32 >jobs.jsonl
  rm -rf out
  start=$(date +%s.%N)
  kib=$(/usr/bin/time -f %M "$facet" batch jobs.jsonl --quiet 2>&1 >/dev/null | tail -n 1)
  seconds=$(echo "$(date +%s.%N) - $start" | bc -l)
  made=$(find out -name '*.png' | wc -l)
  [ "$made" = "$n" ] || { echo "batch_memory: $made of $n images made" >&2; exit 1; }
  [ -z "$base" ] && base=$kib
  printf '%8d %12d %10.1f %14.4f\n' "$n" "$kib" "$seconds" "$(echo "($kib - $base) / ($n - 999)" | bc -l)"
done
