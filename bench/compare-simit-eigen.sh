#!/usr/bin/env bash
# Times simit-run against the Eigen implementation on the same scene, side by
# side in one run: ROUNDS alternating runs of each, N frames per run; each run
# reports the median ms/frame of frames 2..N, and the script prints the median
# over rounds of both, their ratio (simit / eigen), and each one's assembly
# and solve parts (simit-run --time; the Eigen step's own timers), and
# simit-run's compile time without the compile cache (--no-cache).
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

printf '%-14s %10s %10s %7s | %9s %9s | %9s %9s | %10s\n' scene simit_ms eigen_ms ratio \
  simit_asm simit_sol eigen_asm eigen_sol compile_ms
for scene in ${SCENES:-springs-bunny fem-dragon}; do
  for f in simit eigen compile simit_asm simit_sol eigen_asm eigen_sol; do : > "$out/$f"; done
  for ((r = 0; r < rounds; r++)); do
    log=$("$build/bin/simit-run" --scene "$(scene_file "$scene")" --frames "$frames" \
      --time --no-progress --no-cache --output-dir "$out")
    sed -n 's/^frame: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit"
    sed -n 's/^  assembly: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit_asm"
    sed -n 's/^  solve: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/simit_sol"
    sed -n 's/^compile: *\([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/compile"
    log=$("$build/bin/simit-bench-eigen" --scene "$scene" --frames "$frames")
    sed -n 's/^median .*total \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen"
    sed -n 's/^median .*assembly \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen_asm"
    sed -n 's/^median .*solve \([0-9.]*\) ms.*/\1/p' <<<"$log" >> "$out/eigen_sol"
  done
  m() { median < "$out/$1"; }
  s=$(m simit); e=$(m eigen)
  printf '%-14s %10.2f %10.2f %7.2f | %9.2f %9.2f | %9.2f %9.2f | %10.1f\n' "$scene" "$s" "$e" \
    "$(awk -v s="$s" -v e="$e" 'BEGIN {print s / e}')" \
    "$(m simit_asm)" "$(m simit_sol)" "$(m eigen_asm)" "$(m eigen_sol)" "$(m compile)"
done
