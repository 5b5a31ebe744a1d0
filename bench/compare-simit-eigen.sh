#!/usr/bin/env bash
# Times simit-run against the Eigen implementation on the same scene, side by
# side in one run: ROUNDS alternating runs of each, N frames per run; each run
# reports the median ms/frame of frames 2..N, and the script prints the median
# over rounds of both and their ratio (simit / eigen).
#
#   bench/compare-simit-eigen.sh [build-dir]   (default: <repo>/build)
#   SCENES="springs-bunny fem-dragon"  FRAMES=20  ROUNDS=3
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$repo/build}"
frames="${FRAMES:-20}"
rounds="${ROUNDS:-3}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

scene_file() {
  case "$1" in
    springs-bunny) echo "$repo/examples/springs/springs-bunny.json" ;;
    fem-dragon) echo "$repo/examples/fem/fem-dragon.json" ;;
    fem-bar) echo "$repo/examples/fem/fem-bar.json" ;;
    *) echo "unknown scene $1" >&2; exit 1 ;;
  esac
}
median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }

printf '%-14s %12s %12s %8s %12s\n' scene simit_ms eigen_ms ratio compile_ms
for scene in ${SCENES:-springs-bunny fem-dragon}; do
  : > "$out/simit"; : > "$out/eigen"; : > "$out/compile"
  for ((r = 0; r < rounds; r++)); do
    log=$("$build/bin/simit-run" --scene "$(scene_file "$scene")" --frames "$frames" \
      --time --no-progress --output-dir "$out")
    sed -n 's/^frame: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit"
    sed -n 's/^compile: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/compile"
    "$build/bin/simit-bench-eigen" --scene "$scene" --frames "$frames" |
      sed -n 's/^median .*total \([0-9.]*\) ms.*/\1/p' >> "$out/eigen"
  done
  s=$(median < "$out/simit"); e=$(median < "$out/eigen"); c=$(median < "$out/compile")
  printf '%-14s %12.2f %12.2f %8.2f %12.1f\n' "$scene" "$s" "$e" \
    "$(awk -v s="$s" -v e="$e" 'BEGIN {print s / e}')" "$c"
done
