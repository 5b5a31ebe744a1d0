#!/usr/bin/env bash
# Builds simit-bench-eigen and runs the three benchmark scenes of
# ../shared/bench/scenes.md, each with its CG iteration cap and with the
# error against an exact (direct) solve, then prints one table.
#
#   bench/run-bench.sh [build-dir]      (default: <repo>/build)
#   FRAMES=N  frames per scene (default 10; the median is over frames 2..N)
#   EXTRA="--float32"  extra options for every run
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build}"
frames="${FRAMES:-10}"

if [[ ! -f "$build/build.ninja" ]]; then
  cmake -G Ninja -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
ninja -C "$build" -j2 simit-bench-eigen >/dev/null

results=()
for scene in springs-bunny fem-dragon fem-bar; do
  echo "== $scene" >&2
  # shellcheck disable=SC2086
  output="$("$build/bin/simit-bench-eigen" --scene "$scene" --frames "$frames" \
    --reference-direct ${EXTRA:-})"
  echo "$output" | grep -v '^RESULT' >&2
  results+=("$(echo "$output" | grep '^RESULT')")
done

field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<"$2"; }
echo
printf '%-14s %-8s %-7s %5s %9s %9s %12s %9s %9s %6s %11s\n' scene precision \
  solver cap mesh_ms setup_ms assembly_ms solve_ms total_ms iters error
for line in "${results[@]}"; do
  printf '%-14s %-8s %-7s %5s %9s %9s %12s %9s %9s %6s %11s\n' \
    "$(field scene "$line")" "$(field precision "$line")" \
    "$(field solver "$line")" "$(field cap "$line")" \
    "$(field mesh_ms "$line")" "$(field setup_ms "$line")" \
    "$(field assembly_ms "$line")" "$(field solve_ms "$line")" \
    "$(field total_ms "$line")" "$(field iterations "$line")" \
    "$(field error "$line")"
done
